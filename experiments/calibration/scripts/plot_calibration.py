#!/usr/bin/env python3
"""Charts of a `weavelab calibrate` output folder (docs/calibration.md):
curves.png/.svg   yarn-level response, fitted continuum and first guess, per test;
validation.png/.svg  RMS yarn-vs-continuum distance per frame, per validation
                     scene and continuum variant (when validation.csv exists).
Usage: plot_calibration.py DIR
"""
import argparse
import csv
import math
import os
import sys
from collections import OrderedDict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read_rows(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def number(text):
    return float(text) if text not in ("", None) else math.nan


def plot_curves(rows, out):
    tests = OrderedDict()
    for r in rows:
        tests.setdefault(r["test"], []).append(r)
    n = len(tests)
    cols = min(3, n)
    nrows = math.ceil(n / cols)
    fig, axes = plt.subplots(nrows, cols, figsize=(4.2 * cols, 3.4 * nrows), squeeze=False)
    for ax, (name, rs) in zip(axes.flat, tests.items()):
        x = [number(r["load"]) for r in rs]
        ax.plot(x, [number(r["yarn"]) for r in rs], "o", color="black", label="yarn level")
        ax.plot(x, [number(r["fitted"]) for r in rs], "-", color="tab:blue", label="continuum, calibrated")
        ax.plot(x, [number(r["first_guess"]) for r in rs], "--", color="tab:orange", label="continuum, first guess")
        unit = rs[0]["load_unit"]
        ax.set_xlabel("strain" if unit == "1" else ("shear angle [rad]" if unit == "rad" else "curvature [1/m]"))
        ax.set_ylabel(("force per width" if rs[0]["response_unit"] == "N/m" else "moment per width")
                      + f" [{rs[0]['response_unit']}]")
        ax.set_title(name)
        ax.grid(alpha=0.3)
    for ax in list(axes.flat)[n:]:
        ax.axis("off")
    axes.flat[0].legend(fontsize=8)
    fig.tight_layout()
    for ext in ("png", "svg"):
        fig.savefig(f"{out}.{ext}", dpi=120)
    plt.close(fig)


def plot_validation(rows, out):
    scenes = OrderedDict()
    for r in rows:
        scenes.setdefault(r["scene"], OrderedDict()).setdefault(r["variant"], []).append(r)
    fig, axes = plt.subplots(1, len(scenes), figsize=(5.5 * len(scenes), 3.8), squeeze=False)
    styles = {"first_guess": ("--", "tab:orange"), "calibrated_stiffness": (":", "tab:green"),
              "calibrated": ("-", "tab:blue")}
    for ax, (scene, variants) in zip(axes.flat, scenes.items()):
        for name, rs in variants.items():
            ls, colour = styles.get(name, ("-", None))
            ax.plot([number(r["time_s"]) for r in rs], [1e3 * number(r["rms_m"]) for r in rs], ls, color=colour,
                    label=name.replace("_", " "))
        ax.set_xlabel("time [s]")
        ax.set_ylabel("RMS distance to the yarn level [mm]")
        ax.set_title(scene)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
    fig.tight_layout()
    for ext in ("png", "svg"):
        fig.savefig(f"{out}.{ext}", dpi=120)
    plt.close(fig)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("dir", help="output folder of weavelab calibrate")
    a = parser.parse_args(argv)
    curves = os.path.join(a.dir, "curves.csv")
    if not os.path.isfile(curves):
        print(f"plot_calibration.py: {curves}: no such file (run weavelab calibrate first)", file=sys.stderr)
        return 2
    plot_curves(read_rows(curves), os.path.join(a.dir, "curves"))
    validation = os.path.join(a.dir, "validation.csv")
    if os.path.isfile(validation):
        plot_validation(read_rows(validation), os.path.join(a.dir, "validation"))
    return 0


if __name__ == "__main__":
    sys.exit(main())
