#!/usr/bin/env python3
"""Chart of a `weavelab fit` output folder (docs/calibration.md §7):
fit.png/.svg  left: RMS distance to the target per Ceres iteration (one line
              per stage of a growing window, over that stage's frames);
              right: the point that moves most, target against the start and
              the fitted trajectory (its coordinate with the largest motion),
              with the RMS distance of all points per frame.
Usage: plot_fit.py DIR
"""
import argparse
import csv
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from runs import fail, save_figure  # noqa: E402


def read_rows(path):
    try:
        with open(path, newline="") as f:
            return list(csv.DictReader(f))
    except OSError as e:
        fail(f"{path}: {e.strerror}")


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("dir", help="output folder of `weavelab fit`")
    a = ap.parse_args()
    conv = read_rows(os.path.join(a.dir, "convergence.csv"))
    frames = read_rows(os.path.join(a.dir, "frames.csv"))
    with open(os.path.join(a.dir, "fit.json")) as f:
        meta = json.load(f)
    if not conv or not frames:
        fail(f"{a.dir}: convergence.csv or frames.csv has no rows")

    fig, (left, right) = plt.subplots(1, 2, figsize=(11, 4.2))
    stages = {}  # stage → rows; folders written before the growing window have no stage column
    for r in conv:
        stages.setdefault(int(r.get("stage", 1)), []).append(r)
    at = 0
    for stage, rows in sorted(stages.items()):
        it = [at + int(r["iteration"]) for r in rows]
        label = f"stage {stage}: {rows[0]['frames']} frames" if len(stages) > 1 else None
        left.semilogy(it, [float(r["rms_m"]) * 1e3 for r in rows], "o-", label=label)
        at = it[-1] + 1
    if len(stages) > 1:
        left.legend(fontsize=8)
    left.set_xlabel("Ceres iteration" + (" (stages one after the other)" if len(stages) > 1 else ""))
    left.set_ylabel("RMS distance to the target [mm]")
    left.set_title(f"{meta['model']} model, {meta['frames']} frames, {meta['simulations']} simulations, "
                   f"{meta['wall_s']:.0f} s", fontsize=9)
    left.grid(True, which="both", alpha=0.3)

    t = [float(r["time_s"]) for r in frames]
    axis = max("xyz", key=lambda c: max(abs(float(r[f"target_{c}"]) - float(frames[0][f"target_{c}"]))
                                          for r in frames))
    start = "start of the last stage" if len(stages) > 1 else "start"  # frames.csv holds the last stage's
    for who, style, label in (("target", "k-", "target"), ("start", "C1--", start), ("fitted", "C0:", "fitted")):
        right.plot(t, [float(r[f"{who}_{axis}"]) * 1e3 for r in frames], style, label=label, lw=2)
    right.set_xlabel("time [s]")
    right.set_ylabel(f"{axis} of point {frames[0]['point']} [mm]")
    right.legend(loc="upper left", fontsize=8)
    twin = right.twinx()
    twin.semilogy(t, [max(float(r["start_rms_m"]), 1e-15) * 1e3 for r in frames], "C1.", alpha=0.5)
    twin.semilogy(t, [max(float(r["final_rms_m"]), 1e-15) * 1e3 for r in frames], "C0.", alpha=0.5)
    twin.set_ylabel("RMS distance per frame [mm] (dots)")
    fig.tight_layout()
    save_figure(fig, os.path.join(a.dir, "fit.png"))
    print(f"plot_fit.py: {os.path.join(a.dir, 'fit.png')}", file=sys.stderr)


if __name__ == "__main__":
    main()
