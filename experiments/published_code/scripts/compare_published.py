#!/usr/bin/python3
"""Distance of lab runs from the authors' published code, as a fraction of the motion.

    compare_published.py --published DIR --run LABEL=RUN_DIR [--run ...] --reference LABEL \
        --out CSV --plot PNG

DIR holds the driver's trajectory.csv (step, node (i, j), positions). Each RUN_DIR is a
`weavelab run` folder of the same scene with a frame at every step (output_interval = dt),
written with --error-estimate. Frames pair by step (frame time = step · dt); nodes by (i, j),
the lab's point id being i + nu·j.

For every run, per step k: d(k) = RMS over nodes of |x_run − x_published|, and the motion
m(k) = RMS over nodes of |x_published(k) − x_published(0)|. The CSV row gives
max_k d(k), the fraction max d / max m (the figure the issue quotes), the same distance from
the reference run (the lab's default) as a fraction of the motion, and the run's own estimated
time error (summary.json: mean and worst over frames of the RMS, and the worst as a fraction of
the motion). The plot shows d(k)/max m for every run with its time error.
Missing or malformed inputs: a message on stderr and exit 2.
"""
import argparse
import csv
import json
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "common"))
import runs  # noqa: E402


def read_published(folder):
    """{step: (nodes, 3) positions ordered i + nu·j} and nu."""
    path = os.path.join(folder, "trajectory.csv")
    if not os.path.isfile(path):
        runs.fail(f"'{path}' is missing: run the published driver first")
    rows = {}
    nu = 0
    with open(path, newline="") as f:
        for row in csv.DictReader(f):
            try:
                step, i, j = int(row["step"]), int(row["i"]), int(row["j"])
                x = (float(row["x"]), float(row["y"]), float(row["z"]))
            except (KeyError, ValueError) as e:
                runs.fail(f"'{path}': bad row {row}: {e}")
            rows.setdefault(step, {})[(i, j)] = x
            nu = max(nu, i + 1)
    steps = {}
    for step, nodes in rows.items():
        nv = len(nodes) // nu
        steps[step] = np.array([nodes[(k % nu, k // nu)] for k in range(nu * nv)])
    return steps, nu


def read_lab(run_dir, dt):
    """{step: (nodes, 3)} of a lab run, and its summary."""
    summary = runs.read_summary(run_dir, required=True)
    frames = {}
    for t, mesh in runs.read_frames(run_dir):
        step = int(round(t / dt))
        if abs(step * dt - t) > 1e-9 * dt:
            runs.fail(f"'{run_dir}': frame at t = {t} s is not on a step of {dt} s")
        frames[step] = np.asarray(mesh.points, dtype=float)
    return frames, summary


def rms(a, b):
    return float(np.sqrt(np.mean(np.sum((a - b) ** 2, axis=1))))


def distances(frames, reference, steps):
    return np.array([rms(frames[k], reference[k]) for k in steps])


def parse_runs(items):
    out = []
    for item in items:
        label, sep, folder = item.partition("=")
        if not sep or not label or not folder:
            runs.fail(f"--run '{item}': expected LABEL=RUN_DIR")
        out.append((label, folder))
    return out


def plot(path, steps, dt, curves, motion):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(7, 4))
    t = np.asarray(steps) * dt * 1e3
    for label, d, err in curves:
        line, = ax.plot(t, d / motion, label=f"{label}: distance from the published code")
        if err is not None:
            ax.plot(t, err / motion, ls=":", color=line.get_color(), label=f"{label}: own time error")
    ax.set_xlabel("time (ms)")
    ax.set_ylabel("RMS over nodes / largest RMS motion")
    ax.legend(fontsize=7)
    ax.grid(alpha=0.3)
    runs.save_figure(fig, path)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--published", required=True)
    parser.add_argument("--run", action="append", required=True)
    parser.add_argument("--reference", required=True)
    parser.add_argument("--dt", type=float, default=1e-3)
    parser.add_argument("--out", required=True)
    parser.add_argument("--plot")
    args = parser.parse_args()
    published, _ = read_published(args.published)
    labelled = parse_runs(args.run)
    labs = {label: read_lab(folder, args.dt) for label, folder in labelled}
    if args.reference not in labs:
        runs.fail(f"--reference {args.reference}: not among the --run labels")
    steps = sorted(set(published).intersection(*[set(f) for f, _ in labs.values()]))
    if len(steps) < 2:
        runs.fail("fewer than two steps in common between the published trajectory and the runs")
    motion_per_step = np.array([rms(published[k], published[steps[0]]) for k in steps])
    motion = float(motion_per_step.max())
    if motion <= 0.0:
        runs.fail("the published cloth does not move: nothing to compare")
    reference = labs[args.reference][0]
    rows, curves = [], []
    for label, _ in labelled:
        frames, summary = labs[label]
        d = distances(frames, published, steps)
        d_ref = distances(frames, reference, steps)
        te = (summary or {}).get("time_error") or {}
        err = None
        if te.get("rms_m") and te.get("times_s"):
            by_step = {int(round(t / args.dt)): e for t, e in zip(te["times_s"], te["rms_m"])}
            err = np.array([by_step.get(k, 0.0) for k in steps])
        rows.append({
            "run": label,
            "max_rms_distance_to_published_m": float(d.max()),
            "fraction_of_motion": float(d.max()) / motion,
            "fraction_of_motion_from_lab_default": float(d_ref.max()) / motion,
            "time_error_mean_rms_m": te.get("mean_rms_m", ""),
            "time_error_worst_rms_fraction": float(err.max()) / motion if err is not None else "",
            "largest_rms_motion_m": motion,
        })
        curves.append((label, d, err))
    with open(args.out, "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=list(rows[0]))
        writer.writeheader()
        writer.writerows(rows)
    if args.plot:
        plot(args.plot, steps, args.dt, curves, motion)
    print(json.dumps(rows, indent=1))


if __name__ == "__main__":
    main()
