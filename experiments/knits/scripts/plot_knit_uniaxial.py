#!/usr/bin/env python3
"""Knit against woven under the same load per width (the knits study,
experiments/knits/; docs/models.md §11.8). Usage: plot_knit_uniaxial.py OUT

Reads OUT/{knit_y,knit_x,woven_y}/pull.{csv,json}; at loads F/W that every
curve reached, the strain of each (linear interpolation between rungs) and the
ratio knit / woven. Writes OUT/knit_uniaxial.png and OUT/knit_uniaxial.csv (the
table; empty cells where a curve never reached the load) and prints the table."""
import csv
import json
import math
import os
import sys

import numpy as np


def curve(folder):
    rows = list(csv.DictReader(open(os.path.join(folder, "pull.csv"))))
    meta = json.load(open(os.path.join(folder, "pull.json")))
    strain = np.array([float(r["strain"]) for r in rows])
    force = np.array([float(r["force_per_width_N_per_m"]) for r in rows])
    return strain, force, meta


def strain_at(strain, force, load):
    # The first crossing of the load along the ladder (the response may not be monotonic).
    for k in range(1, len(force)):
        if (force[k - 1] - load) * (force[k] - load) <= 0 and force[k] != force[k - 1]:
            return strain[k - 1] + (load - force[k - 1]) * (strain[k] - strain[k - 1]) / (force[k] - force[k - 1])
    return float("nan")


def main():
    out = sys.argv[1]
    names = {"knit_y": "knit, wale-wise", "knit_x": "knit, course-wise", "woven_y": "woven"}
    curves = {k: curve(os.path.join(out, k)) for k in names if os.path.exists(os.path.join(out, k, "pull.csv"))}
    for k, (s, f, m) in list(curves.items()):
        reached = f"{len(s) - 1} rungs to strain {s[-1]:.4g}, F/W {f[-1]:.4g} N/m" if len(s) else "no rung"
        print(f"{names[k]}: yarn length per area {m['yarn_length_per_area_per_m']:.5g} 1/m, grips "
              f"{1e3 * m['grip_distance_m']:.3f} mm apart, {1e3 * m['grip_width_m']:.3f} mm wide; {reached}"
              + ("" if m["complete"] else f"; stopped: {m['message']}"))
        if len(s) < 2:
            del curves[k]
    if "woven_y" not in curves:
        sys.exit("plot_knit_uniaxial.py: no woven curve")
    top = curves["woven_y"][1].max()  # a row per load the woven reaches; a knit that does not: —
    preload = max(f[0] for _, f, _ in curves.values())  # F/W at zero strain (the knit's rest self-stress)
    loads = [x for x in (0.02, 0.05, 0.1, 0.2, 0.5, 1.0, 2.0, 5.0, 10.0) if 2.0 * preload < x <= top]
    print(f"(loads above twice the largest F/W at zero strain, {preload:.3g} N/m: the knit's rest tile pulls on its grips)")
    print("\n| F/W [N/m] | " + " | ".join(f"strain, {names[k]}" for k in curves) + " | " +
          " | ".join(f"{names[k]} / woven" for k in curves if k != "woven_y") + " |")
    print("|---" * (2 * len(curves)) + "|")
    table = [["load_N_per_m"] + [f"strain_{k}" for k in curves] + [f"{k}_over_woven" for k in curves if k != "woven_y"]]
    for load in loads:
        e = {k: strain_at(s, f, load) for k, (s, f, _) in curves.items()}
        ratios = [e[k] / e["woven_y"] for k in curves if k != "woven_y"]
        cell = lambda x, fmt: "—" if math.isnan(x) else format(x, fmt)
        print(f"| {load:g} | " + " | ".join(cell(e[k], ".4g") for k in curves) + " | " +
              " | ".join(cell(r, ".3g") for r in ratios) + " |")
        table.append([f"{load:g}"] + ["" if math.isnan(x) else f"{x:.6g}" for x in [e[k] for k in curves] + ratios])
    with open(os.path.join(out, "knit_uniaxial.csv"), "w", newline="") as f:
        csv.writer(f, lineterminator="\n").writerows(table)
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(5.5, 3.8))
    for k, (s, f, _) in curves.items():
        ax.plot(100 * s[1:], f[1:], "o-", ms=3, label=names[k])
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("strain [%]")
    ax.set_ylabel("pull per width F/W [N/m]")
    ax.set_title("uniaxial strip, same yarn and yarn length per area")
    ax.legend()
    fig.tight_layout()
    fig.savefig(os.path.join(out, "knit_uniaxial.png"), dpi=120)


if __name__ == "__main__":
    main()
