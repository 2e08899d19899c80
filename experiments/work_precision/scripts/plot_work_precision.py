#!/usr/bin/python3
"""Work-precision chart of a `weavelab work-precision` result folder.

Reads DIR/work_precision.csv (and DIR/work_precision.json when present) and
writes DIR/work_precision.png and .svg: RMS position error against CPU time,
log-log, one panel per model, one curve per integrator (runs that did not end
"ok" are left out and listed under the panel). Also writes DIR/slopes.csv and
prints it: per model and integrator the least-squares slope of log error
against log CPU time and against log of the ladder parameter (dt or rtol).

Usage: plot_work_precision.py DIR [--out PREFIX]
"""
import argparse
import csv
import json
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

# One fixed colour and marker per integrator, in documentation order.
STYLE = {
    "be-linear": ("#1f77b4", "o"),
    "be-newton": ("#17becf", "s"),
    "sdirk2": ("#e377c2", "*"),
    "ida": ("#d62728", "D"),
    "arkode-erk": ("#2ca02c", "^"),
    "arkode-dirk": ("#9467bd", "v"),
    "arkode-imex": ("#ff7f0e", "P"),
    "symplectic": ("#8c564b", "X"),
}


def fail(message):
    print(f"plot_work_precision.py: error: {message}", file=sys.stderr)
    sys.exit(2)


def read_rows(folder):
    path = os.path.join(folder, "work_precision.csv")
    if not os.path.exists(path):
        fail(f"'{path}' is missing (run `weavelab work-precision` first)")
    with open(path, newline="", encoding="utf-8") as f:
        rows = list(csv.DictReader(f))
    need = {"model", "integrator", "mode", "rtol", "dt_s", "outcome", "error_rms_m", "cpu_s"}
    if rows and not need <= set(rows[0]):
        fail(f"'{path}' lacks columns {sorted(need - set(rows[0]))}")
    return rows


def read_meta(folder):
    path = os.path.join(folder, "work_precision.json")
    if not os.path.exists(path):
        return {}
    with open(path, encoding="utf-8") as f:
        return json.load(f)


def number(text):
    try:
        return float(text)
    except (TypeError, ValueError):
        return math.nan


def slope(x, y):
    """Least-squares slope of log10 y against log10 x (NaN with < 2 points)."""
    x, y = np.asarray(x, float), np.asarray(y, float)
    keep = (x > 0) & (y > 0)
    if keep.sum() < 2:
        return math.nan
    return float(np.polyfit(np.log10(x[keep]), np.log10(y[keep]), 1)[0])


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("folder", help="result folder of `weavelab work-precision`")
    ap.add_argument("--out", help="output prefix (default FOLDER/work_precision)")
    args = ap.parse_args()
    rows = read_rows(args.folder)
    meta = read_meta(args.folder)
    prefix = args.out or os.path.join(args.folder, "work_precision")

    models = list(dict.fromkeys(r["model"] for r in rows))
    if not models:
        fail("no runs in work_precision.csv")
    fig, axes = plt.subplots(1, len(models), figsize=(6.4 * len(models), 5.6), squeeze=False)
    slopes = []
    for ax, model in zip(axes[0], models):
        mine = [r for r in rows if r["model"] == model]
        missing = []
        for integ, mode in dict.fromkeys((r["integrator"], r["mode"]) for r in mine):
            runs = [r for r in mine if r["integrator"] == integ and r["mode"] == mode]
            ok = [r for r in runs if r["outcome"] == "ok" and number(r["error_rms_m"]) > 0]
            failed = [r for r in runs if r["outcome"] != "ok"]
            if not ok:
                modes = sorted({r["outcome"] for r in failed})
                missing.append(f"{integ}: {', '.join(modes)}")
                continue
            cpu = [number(r["cpu_s"]) for r in ok]
            err = [number(r["error_rms_m"]) for r in ok]
            adaptive = ok[0]["mode"] == "adaptive"
            param = [number(r["rtol"] if adaptive else r["dt_s"]) for r in ok]
            s_cpu, s_par = slope(cpu, err), slope(param, err)
            slopes.append({"model": model, "integrator": integ, "mode": ok[0]["mode"], "points": len(ok),
                           "slope_error_vs_cpu": s_cpu,
                           "slope_error_vs_" + ("rtol" if adaptive else "dt"): s_par})
            colour, marker = STYLE.get(integ, (None, "o"))
            label = f"{integ} ({'rtol' if adaptive else 'dt'} ladder, slope {s_cpu:.2f})" if len(ok) > 1 else integ
            # A method with both ladders: the rtol ladder dashed.
            style = "--" if adaptive and any(r["integrator"] == integ and r["mode"] == "fixed" for r in mine) else "-"
            ax.loglog(cpu, err, marker=marker, color=colour, label=label, linewidth=1.6, markersize=6, linestyle=style)
            published = meta.get("published_dt_s")
            if published and not adaptive:
                for c_, e_, p_ in zip(cpu, err, param):
                    if abs(p_ - published) <= 1e-9 * published:
                        ax.plot([c_], [e_], marker="o", markersize=14, markerfacecolor="none", color="black")
                        ax.annotate("published step", (c_, e_), textcoords="offset points", xytext=(8, 8),
                                    fontsize=7)
            # Label the loosest and the tightest rung.
            for i in sorted({0, len(ok) - 1}):
                if adaptive:
                    tag = f"{param[i]:.0e}"
                else:
                    tag = f"{param[i] * 1e3:.3g} ms" if param[i] >= 1e-3 else f"{param[i] * 1e6:.3g} µs"
                below = i > 0 and not adaptive  # the fine end of a dt ladder: label below the point
                ax.annotate(tag, (cpu[i], err[i]), textcoords="offset points", xytext=(5, -11 if below else 4),
                            fontsize=7, color=colour)
            if failed:
                missing.append(f"{integ}: {len(failed)} rung(s) {', '.join(sorted({r['outcome'] for r in failed}))}")
        ref = meta.get("references", {}).get(model, {})
        title = f"{model} model"
        if ref:
            title += f" (reference: ida, rtol {ref.get('rtol', float('nan')):.0e})"
        ax.set_title(title, fontsize=11)
        ax.set_xlabel("CPU time [s]")
        ax.set_ylabel("RMS position error [m]")
        ax.grid(True, which="major", alpha=0.4)
        ax.grid(True, which="minor", alpha=0.12)
        ax.legend(fontsize=8, loc="lower left")
        if missing:
            ax.text(0.99, 0.99, "no error point / failed rungs:\n" + "\n".join(missing), transform=ax.transAxes,
                    ha="right", va="top", fontsize=7, color="0.3",
                    bbox=dict(boxstyle="round", facecolor="white", edgecolor="0.7", alpha=0.9))
    scene = meta.get("scene", {})
    if scene:
        fig.suptitle(f"Work-precision: {scene.get('name', '')}, {scene.get('warps')}×{scene.get('wefts')}, "
                     f"{scene.get('duration_s')} s simulated (git {meta.get('git_revision', '?')})", fontsize=12)
    fig.tight_layout()
    for ext in ("png", "svg"):
        fig.savefig(f"{prefix}.{ext}", dpi=130)
    print(f"wrote {prefix}.png and {prefix}.svg")

    slope_path = os.path.join(os.path.dirname(prefix) or ".", "slopes.csv")
    cols = ["model", "integrator", "mode", "points", "slope_error_vs_cpu", "slope_error_vs_dt", "slope_error_vs_rtol"]
    with open(slope_path + ".tmp", "w", newline="", encoding="utf-8") as f:
        w = csv.DictWriter(f, fieldnames=cols)
        w.writeheader()
        for s in slopes:
            w.writerow({k: (f"{v:.3f}" if isinstance(v, float) else v) for k, v in s.items()})
    os.replace(slope_path + ".tmp", slope_path)
    print(f"{'model':6} {'integrator':12} {'pts':>3} {'err~cpu^':>9} {'err~dt^':>8} {'err~rtol^':>9}")
    for s in slopes:
        print(f"{s['model']:6} {s['integrator']:12} {s['points']:3d} {s['slope_error_vs_cpu']:9.2f} "
              f"{s.get('slope_error_vs_dt', math.nan):8.2f} {s.get('slope_error_vs_rtol', math.nan):9.2f}")


if __name__ == "__main__":
    main()
