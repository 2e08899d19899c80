#!/usr/bin/python3
"""The lab against the authors' published code at steps fine enough to see their difference.

    compare_fine.py --step-s H --published LABEL=DIR_H,DIR_2H,DIR_4H [--published ...] \
        --run LABEL=RUN_DIR_H,RUN_DIR_2H,RUN_DIR_4H [--run ...] --out CSV [--plot PNG]

Each published LABEL names three driver folders (trajectory.csv, solver.csv) of the same scene and
solver at the steps H, 2H and 4H; each lab LABEL three `weavelab run` folders of the same scene at
those steps, with a frame at every step, written with --error-estimate.

Every pair of runs at the same step is compared as in compare_published.py: d(k) = RMS over nodes of
the distance at step k, reported as max_k d(k) over the motion, the largest RMS displacement of the
first published run at H from its initial state. Beside each distance stand both runs' own time
errors as fractions of the same motion: a lab run's from its summary (Richardson against its steps
halved, docs/models.md §7.8); a published run's by the same rule from the next coarser run (first
order: the error at 2S is twice the error at S, so e_S = RMS_nodes |x_2S − x_S| and
e_2S = 2 · RMS_nodes |x_2S − x_S|), worst over steps. A distance well above both time errors is a
difference of the models; one below them is not resolved at that step.

A difference of the steps (their Jacobians, right-hand side and linearization against the lab's)
is first order in the step; one of the forces is not. So the difference field D_S(t) = x_lab,S(t) −
x_published,S(t) is also extrapolated to a zero step, D* = 2 D_H − D_2H at the times of the 2H run
(Richardson, first order), and the error of that extrapolation is estimated from the same one a step
coarser, |(2 D_2H − D_4H) − D*| / 3 at the times of the 4H run (second order): rows with level
"zero step". Rows: at H, 2H and 4H, every lab run against every published run, then every published
run against the first; then the extrapolated rows. The published run's worst relative residual of
its linear solves is a column too.
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

LEVELS = ("H", "2H", "4H")  # the step, as a multiple of H: 1, 2, 4


def parse_levels(items, option):
    """[(label, [dir at H, dir at 2H, dir at 4H])] of LABEL=DIR_H,DIR_2H,DIR_4H items."""
    out = []
    for item in items:
        label, sep, value = item.partition("=")
        folders = value.split(",")
        if not sep or not label or len(folders) != len(LEVELS) or not all(folders):
            runs.fail(f"{option} '{item}': expected LABEL=DIR_H,DIR_2H,DIR_4H")
        out.append((label, folders))
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


def published_runs(label, folders):
    """{level: (trajectory {step: (nodes, 3)}, time error {step: m}, worst solve residual)}."""
    at = [read_published(folder)[0] for folder in folders]
    for fine, coarse, level in zip(at, at[1:], LEVELS[1:]):
        if max(fine) // 2 not in coarse:
            runs.fail(f"--published {label}: the run at {level} does not cover the run a step finer")
    # each level's error from the next coarser run; the coarsest's from the one finer
    errors = [{k: rms(at[0][k], at[1][k // 2]) for k in at[0] if k % 2 == 0 and k // 2 in at[1]}]
    for fine, coarse in zip(at, at[1:]):
        errors.append({k: 2.0 * rms(coarse[k], fine[2 * k]) for k in coarse if 2 * k in fine})
    return {level: (at[n], errors[n], worst_residual(folders[n])) for n, level in enumerate(LEVELS)}


def lab_run(folder, step_s):
    frames, summary = read_lab(folder, step_s)
    te = (summary or {}).get("time_error") or {}
    if not te.get("rms_m") or not te.get("times_s"):
        runs.fail(f"'{folder}': no time error in the summary (run it with --error-estimate)")
    return frames, {int(round(t / step_s)): e for t, e in zip(te["times_s"], te["rms_m"])}


def plot(path, curves, motion):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(7, 4))
    for label, times, d in curves:
        ax.plot(np.asarray(times) * 1e3, d / motion, label=label)
    ax.set_xlabel("time (ms)")
    ax.set_ylabel("RMS distance over nodes / largest RMS motion")
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
    steps_s = {level: args.step_s * 2 ** n for n, level in enumerate(LEVELS)}
    published = {label: published_runs(label, folders) for label, folders in parse_levels(args.published, "--published")}
    labs = {label: {level: lab_run(folder, steps_s[level]) for level, folder in zip(LEVELS, folders)}
            for label, folders in parse_levels(args.run, "--run")}
    first = next(iter(published))
    at_h = published[first]["H"][0]
    motion = max(rms(x, at_h[0]) for x in at_h.values())
    if motion <= 0.0:
        runs.fail("the published cloth does not move: nothing to compare")
    rows, curves, fields = [], [], {}
    for level, step_s in steps_s.items():
        pairs = [(lab, labs[lab][level], name) for name in published for lab in labs]
        pairs += [(f"published ({name})", published[name][level][:2], first) for name in published if name != first]
        for label, (frames, error), name in pairs:
            other, other_error, residual = published[name][level]
            steps = sorted(set(frames) & set(other) & set(error) & set(other_error))
            if len(steps) < 2 or steps[-1] < max(other) - 1:
                runs.fail(f"{label} at {level} = {step_s} s: the runs do not cover each other")
            d = distances(frames, other, steps)
            # the difference field by time (rounded to the finest step), for the extrapolation
            fields[(label, name, level)] = {round(k * 2 ** LEVELS.index(level)): frames[k] - other[k] for k in steps}
            rows.append({
                "run": label, "against": f"published ({name})", "level": level, "step_s": step_s,
                "duration_s": max(other) * step_s,
                "fraction_of_motion": float(d.max()) / motion,
                "run_time_error_worst_fraction": max(error[k] for k in steps) / motion,
                "against_time_error_worst_fraction": max(other_error[k] for k in steps) / motion,
                "against_worst_solve_residual": residual,
                "largest_rms_motion_m": motion,
            })
            curves.append((f"{label} against published ({name}), step {step_s * 1e3:g} ms",
                           np.asarray(steps) * step_s, d))
    for label, name in [(label, name) for label, name, level in fields if level == "H"]:
        d_h, d_2h, d_4h = (fields[(label, name, level)] for level in LEVELS)
        zero = {t: 2.0 * d_h[t] - d_2h[t] for t in d_2h if t in d_h}
        zero_coarse = {t: 2.0 * d_2h[t] - d_4h[t] for t in d_4h if t in d_2h}
        spread = [float(np.sqrt(np.mean(np.sum((zero[t] - zero_coarse[t]) ** 2, axis=1)))) / 3.0
                  for t in zero_coarse if t in zero]
        size = [float(np.sqrt(np.mean(np.sum(zero[t] ** 2, axis=1)))) for t in sorted(zero)]
        rows.append({
            "run": label, "against": f"published ({name})", "level": "zero step", "step_s": 0.0,
            "duration_s": max(zero) * args.step_s, "fraction_of_motion": max(size) / motion,
            "run_time_error_worst_fraction": max(spread) / motion, "against_time_error_worst_fraction": "",
            "against_worst_solve_residual": "", "largest_rms_motion_m": motion,
        })
    with open(args.out, "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=list(rows[0]))
        writer.writeheader()
        writer.writerows(rows)
    if args.plot:
        plot(args.plot, curves, motion)


if __name__ == "__main__":
    main()
