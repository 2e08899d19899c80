#!/usr/bin/python3
"""The lab against the authors' published code at a step fine enough to see their difference.

    compare_fine.py --step-s H --published LABEL=DIR_H,DIR_2H [--published ...] \
        --run LABEL=RUN_DIR [--run ...] --out CSV [--plot PNG]

Each published LABEL names a pair of driver folders (trajectory.csv, solver.csv) of the same
scene and solver at the step H and at 2H. Each RUN_DIR is a `weavelab run` folder of the same
scene at the step H with a frame at every step, written with --error-estimate.

Every pair is compared as in compare_published.py: d(k) = RMS over nodes of the distance at step k,
reported as max_k d(k) over the largest RMS displacement of the first published run from its initial
state (the motion). Beside each distance stand both runs' own time errors as fractions of the same
motion: a lab run's from its summary (Richardson against its steps halved, docs/models.md §7.8); a
published run's by the same rule from its two folders: for a first-order step the error at 2H is
twice the error at H, so e_H(k) = RMS_nodes |x_2H(k/2) − x_H(k)| at the even steps, worst over them. A distance well above both time errors is a difference between the
two models (what neither step removes); one below them is not resolved at this step. Rows: every lab
run against every published run, then every published run against the first. The published worst
relative residual of the linear solves at H is a column too.
Missing or malformed inputs: a message on stderr and exit 2.
"""
import argparse
import csv
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "common"))
import runs  # noqa: E402
from compare_published import distances, read_lab, read_published, rms  # noqa: E402


def parse_pairs(items, option):
    out = []
    for item in items:
        label, sep, value = item.partition("=")
        if not sep or not label or not value:
            runs.fail(f"{option} '{item}': expected LABEL=VALUE")
        out.append((label, value))
    return out


def worst_residual(folder):
    path = os.path.join(folder, "solver.csv")
    if not os.path.isfile(path):
        runs.fail(f"'{path}' is missing: run the published driver first")
    with open(path, newline="") as f:
        try:
            return max(float(row["relative_residual"]) for row in csv.DictReader(f))
        except (KeyError, ValueError) as e:
            runs.fail(f"'{path}': bad row: {e}")


def published_run(label, folders):
    """Trajectory at H {step: (nodes, 3)}, its time error per step (Richardson, p = 1), worst residual."""
    fine, sep, coarse = folders.partition(",")
    if not sep or not fine or not coarse:
        runs.fail(f"--published {label}={folders}: expected LABEL=DIR_H,DIR_2H")
    at_h, _ = read_published(fine)
    at_2h, _ = read_published(coarse)
    error = {k: rms(at_h[k], at_2h[k // 2]) for k in at_h if k % 2 == 0 and k // 2 in at_2h}
    if len(error) < 2 or max(error) < max(at_h) - 1:
        runs.fail(f"--published {label}: the run at 2H does not cover the run at H")
    return at_h, error, worst_residual(fine)


def plot(path, step_s, curves, motion):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(7, 4))
    for label, steps, d in curves:
        ax.plot(np.asarray(steps) * step_s * 1e3, d / motion, label=label)
    ax.set_xlabel("time (ms)")
    ax.set_ylabel("RMS distance over nodes / largest RMS motion")
    ax.set_yscale("log")
    ax.legend(fontsize=7)
    ax.grid(alpha=0.3)
    runs.save_figure(fig, path)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--step-s", type=float, required=True)
    parser.add_argument("--published", action="append", required=True)
    parser.add_argument("--run", action="append", default=[])
    parser.add_argument("--out", required=True)
    parser.add_argument("--plot")
    args = parser.parse_args()
    if not args.step_s > 0:
        runs.fail(f"--step-s {args.step_s}: expected a positive step in seconds")
    published = {label: published_run(label, folders) for label, folders in parse_pairs(args.published, "--published")}
    labs = {}
    for label, folder in parse_pairs(args.run, "--run"):
        frames, summary = read_lab(folder, args.step_s)
        te = (summary or {}).get("time_error") or {}
        if not te.get("rms_m") or not te.get("times_s"):
            runs.fail(f"'{folder}': no time error in the summary (run it with --error-estimate)")
        error = {int(round(t / args.step_s)): e for t, e in zip(te["times_s"], te["rms_m"])}
        labs[label] = (frames, error)
    first = next(iter(published))
    steps = sorted(set(published[first][0]).intersection(*[set(p[0]) for p in published.values()],
                                                          *[set(f) for f, _ in labs.values()]))
    if len(steps) < 2:
        runs.fail("fewer than two steps in common between the runs")
    x0 = published[first][0][steps[0]]
    motion = max(rms(published[first][0][k], x0) for k in steps)
    if motion <= 0.0:
        runs.fail("the published cloth does not move: nothing to compare")
    pairs = [(lab, f"published ({name})", labs[lab], published[name][:2]) for name in published for lab in labs]
    pairs += [(f"published ({name})", f"published ({first})", published[name][:2], published[first][:2])
              for name in published if name != first]
    rows, curves = [], []
    for a, b, (frames_a, error_a), (frames_b, error_b) in pairs:
        d = distances(frames_a, frames_b, steps)
        residual = published[b[len("published ("):-1]][2]
        rows.append({
            "run": a, "against": b, "step_s": args.step_s, "duration_s": steps[-1] * args.step_s,
            "fraction_of_motion": float(d.max()) / motion,
            "run_time_error_worst_fraction": max(error_a[k] for k in steps if k in error_a) / motion,
            "against_time_error_worst_fraction": max(error_b[k] for k in steps if k in error_b) / motion,
            "against_worst_solve_residual": residual,
            "largest_rms_motion_m": motion,
        })
        curves.append((f"{a} against {b}", steps, d))
    with open(args.out, "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=list(rows[0]))
        writer.writeheader()
        writer.writerows(rows)
    if args.plot:
        plot(args.plot, args.step_s, curves, motion)


if __name__ == "__main__":
    main()
