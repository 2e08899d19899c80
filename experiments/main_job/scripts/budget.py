#!/usr/bin/python3
"""The main job's comparison: each continuum run against the yarn level, frame
by frame (experiments/common/compare.py), with the error budget.

    budget.py YARN_RUN LABEL=FEM_RUN [LABEL=FEM_RUN ...] --out CSV --frames CSV --text TXT [--plot PNG]

--out: one row per continuum: the distance (mean over the frames after t = 0
of the RMS over the yarn crossings of the distance to the continuum surface at
the same material point), each run's estimated time error (mean over frames
of the RMS, summary.json "time_error", docs/models.md §7.8), both in mm, and
compare.py's verdict on them (the models are resolved apart when both time
errors are below a tenth of the distance). --frames: the per-frame RMS and max distances of every
continuum. --text: the same table as text (printed on stdout too). --plot: the
RMS distance over time, one line per continuum. Missing or malformed runs:
a message on stderr and exit status 2.
"""
import argparse
import csv
import os
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
COMMON = os.path.join(HERE, "..", "..", "common")
sys.path.insert(0, COMMON)
import compare  # noqa: E402
import runs as wio  # noqa: E402

COLUMNS = ["continuum", "distance_mm", "yarn_time_error_mm", "continuum_time_error_mm", "verdict"]


def budget_row(label, yarn, fem):
    """(row for --out, per-frame rows) of one continuum run against the yarn level."""
    frames, _, _ = compare.compare(yarn, fem)
    # compare.error_budget's distance: the mean over the frames after t = 0.
    distance = float(np.mean([r[1] for r in frames[1:]] if len(frames) > 1 else [r[1] for r in frames]))
    errors = [None if e is None else e[0] for e in (compare.time_error(yarn), compare.time_error(fem))]
    mm = lambda x: "" if x is None else f"{1e3 * x:.6g}"  # noqa: E731
    row = {"continuum": label, "distance_mm": mm(distance), "yarn_time_error_mm": mm(errors[0]),
           "continuum_time_error_mm": mm(errors[1]),
           "verdict": compare.error_budget(frames, yarn, fem)[-1].removeprefix("budget: ")}
    return row, [(label, t, rms, mx) for t, rms, mx, _ in frames]


def text_table(rows):
    lines = ["continuum     distance (mm)  yarn time error (mm)  continuum time error (mm)  verdict"]
    for r in rows:
        lines.append(f"{r['continuum']:12s}  {r['distance_mm']:>13s}  {r['yarn_time_error_mm']:>20s}  "
                     f"{r['continuum_time_error_mm']:>25s}  {r['verdict']}")
    return "\n".join(lines) + "\n"


def plot(path, frames, labels):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(7, 4))
    for label in labels:
        t = [f[1] for f in frames if f[0] == label]
        ax.plot(t, [1e3 * f[2] for f in frames if f[0] == label], "o-", ms=3, label=label)
    ax.set_xlabel("time (s)")
    ax.set_ylabel("RMS distance to the yarn level (mm)")
    ax.set_ylim(bottom=0.0)
    ax.grid(True, alpha=0.3)
    ax.legend()
    wio.save_figure(fig, path, svg=False)
    plt.close(fig)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("yarn", help="the yarn-level run folder")
    ap.add_argument("continua", nargs="+", metavar="LABEL=RUN", help="continuum run folders")
    ap.add_argument("--out", required=True)
    ap.add_argument("--frames", required=True)
    ap.add_argument("--text", required=True)
    ap.add_argument("--plot")
    a = ap.parse_args()
    rows, frames = [], []
    try:
        for item in a.continua:
            label, sep, run = item.partition("=")
            if not sep or not label or not run:
                wio.fail(f"got '{item}', expected LABEL=RUN")
            row, per_frame = budget_row(label, a.yarn, run)
            rows.append(row)
            frames += per_frame
    except wio.RunError as e:
        wio.fail(str(e))
    with open(a.out, "w", newline="") as f:
        w = csv.DictWriter(f, COLUMNS, lineterminator="\n")
        w.writeheader()
        w.writerows(rows)
    with open(a.frames, "w", newline="") as f:
        w = csv.writer(f, lineterminator="\n")
        w.writerow(["continuum", "time_s", "rms_distance_m", "max_distance_m"])
        w.writerows(frames)
    text = text_table(rows)
    with open(a.text, "w") as f:
        f.write(text)
    sys.stdout.write(text)
    if a.plot:
        plot(a.plot, frames, [r["continuum"] for r in rows])


if __name__ == "__main__":
    main()
