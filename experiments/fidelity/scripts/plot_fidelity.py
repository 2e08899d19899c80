#!/usr/bin/python3
"""Pareto chart of a `weavelab fidelity` result folder.

Reads DIR/fidelity.csv and DIR/fidelity.json and writes DIR/fidelity.png and
.svg: the worst-frame RMS distance to the reference against CPU time, log-log,
one labelled point per variant (yarn-level and continuum in two colours), the
Pareto front as a step line, the tolerance as a horizontal line and the
cheapest variant within it ringed, and each run's own estimated time error
(when the ladder estimated it) as a hollow marker joined to its point: a
distance at or below the time error does not measure the model. The reference
(distance 0) sits on the bottom edge. Runs that did not end "ok" are listed
under the chart.

Usage: plot_fidelity.py DIR [--out PREFIX]
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

COLOURS = {"yarn": "#1f77b4", "fem": "#d62728"}


def fail(message):
    print(f"plot_fidelity.py: error: {message}", file=sys.stderr)
    sys.exit(2)


def read_inputs(folder):
    csv_path, json_path = os.path.join(folder, "fidelity.csv"), os.path.join(folder, "fidelity.json")
    for p in (csv_path, json_path):
        if not os.path.exists(p):
            fail(f"'{p}' is missing (run `weavelab fidelity` first)")
    with open(csv_path, newline="", encoding="utf-8") as f:
        rows = list(csv.DictReader(f))
    need = {"variant", "model", "cpu_s", "worst_frame_rms_m", "outcome", "on_front"}
    if not rows or not need <= set(rows[0]):
        fail(f"'{csv_path}' is empty or lacks columns {sorted(need - set(rows[0] if rows else {}))}")
    with open(json_path, encoding="utf-8") as f:
        return rows, json.load(f)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("folder")
    ap.add_argument("--out", help="output prefix (default DIR/fidelity)")
    a = ap.parse_args()
    rows, meta = read_inputs(a.folder)
    ok = [r for r in rows if r["outcome"] == "ok" and r["worst_frame_rms_m"] != ""]
    failed = [r for r in rows if r not in ok]
    errors = [float(r["worst_frame_rms_m"]) for r in ok]
    positive = [e for e in errors if e > 0]
    floor = min(positive) / 10 if positive else 1e-9  # where a zero distance is drawn
    shown = lambda e: max(e, floor)  # noqa: E731

    choice = meta.get("cheapest_within_tolerance", {})
    tol = choice.get("tolerance_m")
    fig, ax = plt.subplots(figsize=(7.5, 5.0))
    placed = []  # labelled points (log10 x, log10 y): a label next to one goes below its point
    for r, e in zip(ok, errors):
        x, y = float(r["cpu_s"]), shown(e)
        ax.scatter(x, y, color=COLOURS.get(r["model"], "grey"), zorder=3, s=36)
        near = any(abs(math.log10(x) - px) < 0.1 and abs(math.log10(y) - py) < 0.3 for px, py in placed)
        placed.append((math.log10(x), math.log10(y)))
        ax.annotate(r["variant"] + (" (reference)" if r["variant"] == meta.get("reference") else ""), (x, y),
                    textcoords="offset points", xytext=(5, -11 if near else 4), fontsize=8)
        if r["variant"] == choice.get("variant"):
            ax.scatter(x, y, s=220, facecolors="none", edgecolors="black", linewidths=1.2, zorder=4)
    estimated = [(float(r["cpu_s"]), shown(e), float(r["time_error_worst_frame_rms_m"]))
                 for r, e in zip(ok, errors) if r.get("time_error_worst_frame_rms_m", "") not in ("", "nan")]
    for x, y, t in estimated:
        ax.plot([x, x], [y, shown(t)], color="grey", linewidth=0.8, zorder=2)
        ax.scatter(x, shown(t), marker="v", facecolors="none", edgecolors="grey", s=30, zorder=2)
    if estimated:
        ax.scatter([], [], marker="v", facecolors="none", edgecolors="grey", label="the run's own time error")
    front = sorted((float(r["cpu_s"]), shown(e)) for r, e in zip(ok, errors) if r["on_front"] == "1")
    if front:
        xs, ys = zip(*front)
        ax.step(xs, ys, where="post", color="black", linewidth=1, alpha=0.6, label="Pareto front")
    if tol:
        ax.axhline(tol, color="green", linestyle="--", linewidth=1,
                   label=f"tolerance {1e3 * tol:.3g} mm ({100 * choice['tolerance_of_cloth_size']:.3g} % of the cloth)")
    for model, colour in COLOURS.items():
        ax.scatter([], [], color=colour, label="yarn level" if model == "yarn" else "continuum")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("CPU time [s]")
    ax.set_ylabel("worst-frame RMS distance to the reference [m]")
    scene = os.path.basename(meta.get("scene", {}).get("file", ""))
    ax.set_title(f"Fidelity ladder: {scene}, {meta.get('scene', {}).get('duration_s', '?')} s simulated", fontsize=10)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8, loc="lower left")
    notes = [f"reference at 0 drawn at {floor:.1e} m"]
    notes += [f"{r['variant']}: {r['outcome']}" for r in failed]
    fig.text(0.01, 0.01, "; ".join(notes), fontsize=7)
    fig.tight_layout(rect=(0, 0.03, 1, 1))
    prefix = a.out or os.path.join(a.folder, "fidelity")
    for ext in ("png", "svg"):
        fig.savefig(f"{prefix}.{ext}", dpi=130)
    print(f"plot_fidelity.py: wrote {prefix}.png and .svg")


if __name__ == "__main__":
    main()
