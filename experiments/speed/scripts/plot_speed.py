#!/usr/bin/python3
"""Bar chart of the speed table (speed_table.py --csv): per row the median
wall and CPU time per step, this build on every core and on one thread, log
scale. Usage: plot_speed.py SPEED_TABLE_CSV OUT_PNG (writes .svg beside it too).
"""
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main(table, out):
    with open(table, newline="", encoding="utf-8") as f:
        rows = [r for r in csv.DictReader(f) if r["unit"] == "ms per step"]
    if not rows:
        sys.exit(f"plot_speed.py: error: {table}: no row in ms per step")
    labels = list(dict.fromkeys(r["label"] for r in rows))
    builds = list(dict.fromkeys(r["build"] for r in rows))
    fig, ax = plt.subplots(figsize=(8, 3.8))
    width = 0.8 / (2 * len(builds))
    for b, build in enumerate(builds):
        for q, (column, hatch) in enumerate((("wall", ""), ("cpu", "//"))):
            xs, ys = [], []
            for i, label in enumerate(labels):
                for r in rows:
                    if r["label"] == label and r["build"] == build:
                        xs.append(i + (2 * b + q - len(builds) + 0.5) * width)
                        ys.append(float(r[column]))
            ax.bar(xs, ys, width, label=f"{build}: {column}", hatch=hatch, color=f"C{b}", alpha=0.9 - 0.3 * q)
    ax.set_yscale("log")
    ax.set_xticks(range(len(labels)), labels)
    ax.set_ylabel("be-linear step [ms]")
    ax.grid(axis="y", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    for ext in ("png", "svg"):
        fig.savefig(os.path.splitext(out)[0] + "." + ext, dpi=110)


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(*sys.argv[1:])
