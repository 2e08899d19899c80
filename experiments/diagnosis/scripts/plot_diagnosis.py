#!/usr/bin/python3
"""Charts of a `weavelab diagnose` result folder.

Reads DIR/distance.csv, DIR/rows.csv, DIR/energies.csv and DIR/diagnosis.json
and writes DIR/diagnosis.png and .svg: the distance between the yarn crossings
and the continuum over time (all crossings, border, interior) with both runs'
time errors as horizontal lines, the distance by row of crossings (0 = the held
top row), and per energy quantity (kinetic, stretch, shear, bending, the work of
the wind and of the dissipative terms) its change since t = 0 for both models;
stretch and bending also split into warp and weft (DIR/energy_directions.csv).

Usage: plot_diagnosis.py DIR [--out PREFIX]
"""
import argparse
import csv
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

# The quantities drawn, each with the term names of the two models it gathers.
QUANTITIES = [
    ("kinetic", {"kinetic"}),
    ("stretch", {"stretch", "fem-stretch", "fem-border-stretch"}),
    ("shear", {"shear", "fem-shear"}),
    ("bending", {"bending", "fem-bending"}),
    ("work of the wind", {"work of wind"}),
    ("work of friction and damping", {"work of friction", "work of yarn_damping"}),
]


def fail(message):
    print(f"plot_diagnosis.py: error: {message}", file=sys.stderr)
    sys.exit(2)


def read_csv(folder, name):
    path = os.path.join(folder, name)
    if not os.path.exists(path):
        fail(f"'{path}' is missing (run `weavelab diagnose` first)")
    with open(path, newline="", encoding="utf-8") as f:
        return list(csv.DictReader(f))


def energy_series(rows):
    """{(model, quantity): (times, values)} with values summed over the gathered terms, minus t = 0."""
    per = {}
    for r in rows:
        for label, names in QUANTITIES:
            if r["quantity"] in names:
                key = (r["model"], label)
                per.setdefault(key, {})
                t = float(r["time_s"])
                per[key][t] = per[key].get(t, 0.0) + float(r["value_J"])
    out = {}
    for key, by_time in per.items():
        times = sorted(by_time)
        out[key] = (times, [by_time[t] - by_time[times[0]] for t in times])
    return out


def direction_series(folder):
    """{(model, "stretch" | "bending", "warp" | "weft"): (times, changes since t = 0)}, or {} without the file."""
    if not os.path.exists(os.path.join(folder, "energy_directions.csv")):
        return {}
    per = {}
    for r in read_csv(folder, "energy_directions.csv"):
        kind = "bending" if r["term"].endswith("bending") else "stretch"
        for direction in ("warp", "weft"):
            per.setdefault((r["model"], kind, direction), []).append((float(r["time_s"]), float(r[f"{direction}_J"])))
    return {k: ([t for t, _ in v], [e - v[0][1] for _, e in v]) for k, v in per.items()}


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("folder")
    ap.add_argument("--out", help="output prefix (default DIR/diagnosis)")
    a = ap.parse_args()
    distance = read_csv(a.folder, "distance.csv")
    rows = read_csv(a.folder, "rows.csv")
    energies = energy_series(read_csv(a.folder, "energies.csv"))
    directions = direction_series(a.folder)
    meta_path = os.path.join(a.folder, "diagnosis.json")
    if not os.path.exists(meta_path):
        fail(f"'{meta_path}' is missing (run `weavelab diagnose` first)")
    with open(meta_path, encoding="utf-8") as f:
        meta = json.load(f)

    fig = plt.figure(figsize=(12, 7.5))
    grid = fig.add_gridspec(3, 4)
    ax = fig.add_subplot(grid[0, :2])
    t = [float(r["time_s"]) for r in distance]
    for column, label in (("rms_m", "all crossings"), ("border_rms_m", "border"), ("interior_rms_m", "interior")):
        ax.plot(t, [1e3 * float(r[column]) for r in distance], label=label)
    for model, style in (("yarn", ":"), ("fem", "--")):
        e = meta.get(f"{model}_time_error", {}).get("mean_rms_m")
        if e is not None:
            ax.axhline(1e3 * e, color="grey", linestyle=style, linewidth=1, label=f"{model} time error (mean RMS)")
    ax.set_xlabel("t [s]")
    ax.set_ylabel("RMS distance [mm]")
    ax.set_title(f"yarn crossings to the continuum: {meta.get('verdict', '')}", fontsize=9)
    ax.legend(fontsize=7)
    ax.grid(alpha=0.3)

    ax = fig.add_subplot(grid[0, 2:])
    ax.plot([int(r["row"]) for r in rows], [1e3 * float(r["rms_m"]) for r in rows], marker="o")
    ax.set_xlabel("row of crossings (0 = held top row)")
    ax.set_ylabel("RMS distance over the run [mm]")
    ax.grid(alpha=0.3)

    for k, (label, _) in enumerate(QUANTITIES):
        ax = fig.add_subplot(grid[1 + k // 3, (k % 3) * 4 // 3:((k % 3) + 1) * 4 // 3])
        for model, style in (("yarn", "-"), ("fem", "--")):
            if (model, label) in energies:
                times, values = energies[(model, label)]
                ax.plot(times, [1e6 * v for v in values], style, label=model)
            for direction, marker in (("warp", "^"), ("weft", "v")):
                if (model, label, direction) in directions:
                    times, values = directions[(model, label, direction)]
                    ax.plot(times, [1e6 * v for v in values], style, marker=marker, markevery=max(1, len(times) // 8),
                            markersize=4, linewidth=0.8, label=f"{model} {direction}")
        ax.set_title(label, fontsize=9)
        ax.set_xlabel("t [s]", fontsize=8)
        ax.set_ylabel("change since t = 0 [µJ]", fontsize=8)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7)
    scene = os.path.basename(meta.get("scene", {}).get("file", ""))
    fig.suptitle(f"Where the continuum parts from the yarn level: {scene}, {meta.get('resolution', '')}", fontsize=10)
    fig.tight_layout()
    prefix = a.out or os.path.join(a.folder, "diagnosis")
    for ext in ("png", "svg"):
        fig.savefig(f"{prefix}.{ext}", dpi=110)
    print(f"plot_diagnosis.py: wrote {prefix}.png and .svg")


if __name__ == "__main__":
    main()
