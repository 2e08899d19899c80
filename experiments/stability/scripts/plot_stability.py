#!/usr/bin/python3
"""Stability heat map of a `weavelab stability` result folder.

Reads DIR/stability.csv (and DIR/stability.json when present) and writes
DIR/stability.png and .svg: rows integrator × model, columns stretch-modulus
multiplier, colour = log10 of the largest fixed step found bounded, each cell
annotated with that step and the failure mode just above it ("≥" when even the
largest step probed was bounded; "none" when no step down to dt_min was;
grey = not offered).

Usage: plot_stability.py DIR [--out PREFIX]
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

SHORT = {  # failure modes as cell text
    "ARK_CONV_FAILURE": "ARK_CONV_FAIL",
    "ARK_ERR_FAILURE": "ARK_ERR_FAIL",
    "not_offered": "not offered",
}


def fail(message):
    print(f"plot_stability.py: error: {message}", file=sys.stderr)
    sys.exit(2)


def number(text):
    try:
        return float(text)
    except (TypeError, ValueError):
        return math.nan


def fmt_dt(dt):
    if dt >= 1e-3:
        return f"{dt * 1e3:.3g} ms"
    return f"{dt * 1e6:.3g} µs"


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("folder", help="result folder of `weavelab stability`")
    ap.add_argument("--out", help="output prefix (default FOLDER/stability)")
    args = ap.parse_args()
    path = os.path.join(args.folder, "stability.csv")
    if not os.path.exists(path):
        fail(f"'{path}' is missing (run `weavelab stability` first)")
    with open(path, newline="", encoding="utf-8") as f:
        rows = list(csv.DictReader(f))
    if not rows:
        fail(f"no cells in '{path}'")
    meta = {}
    meta_path = os.path.join(args.folder, "stability.json")
    if os.path.exists(meta_path):
        with open(meta_path, encoding="utf-8") as f:
            meta = json.load(f)
    params = meta.get("parameters", {})
    dt_min = params.get("dt_min_s", 1e-6)
    dt_max = params.get("dt_max_s", 1e-2)

    integrators = list(dict.fromkeys(r["integrator"] for r in rows))
    models = list(dict.fromkeys(r["model"] for r in rows))
    mults = sorted({number(r["multiplier"]) for r in rows})
    labels = [(i, m) for i in integrators for m in models]
    cell = {(r["integrator"], r["model"], number(r["multiplier"])): r for r in rows}

    value = np.full((len(labels), len(mults)), np.nan)
    fig, ax = plt.subplots(figsize=(2.0 + 1.9 * len(mults), 1.2 + 0.52 * len(labels)))
    cmap = plt.get_cmap("viridis").copy()
    cmap.set_bad("0.85")
    for y, (integ, model) in enumerate(labels):
        for x, mult in enumerate(mults):
            r = cell.get((integ, model, mult))
            if r is None:
                continue
            dt = number(r["largest_stable_dt_s"])
            mode = r.get("failure_mode", "")
            if mode == "not_offered":
                text = "not offered"
            elif math.isnan(dt):
                text = f"none ≥ {fmt_dt(dt_min)}\n{SHORT.get(mode, mode)}"
                value[y, x] = math.log10(dt_min) - 0.25  # below the scale: darkest colour
            else:
                value[y, x] = math.log10(dt)
                bounded_top = not r.get("smallest_unstable_dt_s")
                text = ("≥ " if bounded_top else "") + fmt_dt(dt)
                if not bounded_top:
                    text += "\n" + SHORT.get(mode, mode)
            if mode == "not_offered":
                ax.text(x, y, text, ha="center", va="center", fontsize=8, color="0.35")
            else:
                v = value[y, x]
                frac = (v - math.log10(dt_min)) / (math.log10(dt_max) - math.log10(dt_min))
                ax.text(x, y, text, ha="center", va="center", fontsize=8,
                        color="white" if frac < 0.6 else "black")
    im = ax.imshow(np.ma.masked_invalid(value), cmap=cmap, aspect="auto",
                   vmin=math.log10(dt_min) - 0.25, vmax=math.log10(dt_max))
    ax.set_xticks(range(len(mults)))
    ax.set_xticklabels([f"×{m:g}" for m in mults])
    ax.set_yticks(range(len(labels)))
    ax.set_yticklabels([f"{i} / {m}" for i, m in labels], fontsize=9)
    ax.set_xlabel("stretch-modulus multiplier")
    ax.set_xticks(np.arange(-0.5, len(mults)), minor=True)
    ax.set_yticks(np.arange(-0.5, len(labels)), minor=True)
    ax.grid(which="minor", color="white", linewidth=1.5)
    ax.tick_params(which="minor", length=0)
    for y in range(len(models), len(labels), len(models)):
        ax.axhline(y - 0.5, color="black", linewidth=1.2)
    cb = fig.colorbar(im, ax=ax, pad=0.02)
    cb.set_label("log10 largest bounded fixed step [s]")
    scene = meta.get("scene", {})
    title = "Stability: largest bounded fixed step, failure mode above it"
    if scene:
        title += (f"\n{scene.get('name', '')}, {scene.get('warps')}×{scene.get('wefts')}, "
                  f"{scene.get('duration_s')} s, bound {params.get('speed_bound_m_per_s', '?')} m/s "
                  f"(git {meta.get('git_revision', '?')})")
    ax.set_title(title, fontsize=10)
    fig.tight_layout()
    prefix = args.out or os.path.join(args.folder, "stability")
    for ext in ("png", "svg"):
        fig.savefig(f"{prefix}.{ext}", dpi=130)
    print(f"wrote {prefix}.png and {prefix}.svg")


if __name__ == "__main__":
    main()
