#!/usr/bin/python3
"""Distance of lab runs from the authors' published code, as a fraction of the motion.

    compare_published.py --published DIR --run LABEL=RUN_DIR [--run ...] --reference LABEL \
        [--compat-reference LABEL --corrections CSV --corrections-plot PNG] --out CSV --plot PNG

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

With --compat-reference (the run with every [compat] switch, the published model), each run's
distance from it is a column too, and --corrections writes the worth of each correction: for every
run labelled without_X (the published model with correction X alone), its displacement field
D_X(k) = x_without_X(k) − x_compat(k) as max_k RMS / max m; then the sum Σ_X D_X against the
displacement of all corrections together, D(k) = x_reference(k) − x_compat(k), and the RMS of
their difference (the part of the total that the separate effects do not account for), each as a
fraction of the motion beside the worst time error of the runs involved.
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
        if label.startswith("without_"):
            continue  # in the corrections chart
        line, = ax.plot(t, d / motion, label=f"{label}: distance from the published code")
        if err is not None:
            ax.plot(t, err / motion, ls=":", color=line.get_color(), label=f"{label}: own time error")
    ax.set_xlabel("time (ms)")
    ax.set_ylabel("RMS over nodes / largest RMS motion")
    ax.legend(fontsize=7)
    ax.grid(alpha=0.3)
    runs.save_figure(fig, path)


def field(frames, base, steps):
    """Displacement field frames(k) − base(k) over the steps, shape (steps, nodes, 3)."""
    return np.array([frames[k] - base[k] for k in steps])


def largest_rms(field_):
    return float(np.sqrt(np.mean(np.sum(field_ ** 2, axis=2), axis=1)).max())


def write_corrections(path, labs, steps, total_label, compat_label, motion, worst_error, plot_path=None):
    """Worth of each correction and whether the separate effects add up to the total."""
    compat = labs[compat_label][0]
    corrections = [label for label in labs if label.startswith("without_")]
    if not corrections:
        runs.fail("--corrections: no run labelled without_*")
    rows, total_sum = [], np.zeros((len(steps),) + compat[steps[0]].shape)
    for label in corrections:
        d = field(labs[label][0], compat, steps)
        total_sum += d
        rows.append({"correction": label[len("without_"):], "fraction_of_motion": largest_rms(d) / motion,
                     "worst_time_error_fraction": max(worst_error[label], worst_error[compat_label])})
    total = field(labs[total_label][0], compat, steps)
    involved = max(worst_error[label] for label in corrections + [compat_label, total_label])
    rows.append({"correction": "sum of the separate effects", "fraction_of_motion": largest_rms(total_sum) / motion,
                 "worst_time_error_fraction": involved})
    rows.append({"correction": f"all together ({total_label})", "fraction_of_motion": largest_rms(total) / motion,
                 "worst_time_error_fraction": max(worst_error[total_label], worst_error[compat_label])})
    rows.append({"correction": "sum minus all together", "fraction_of_motion": largest_rms(total_sum - total) / motion,
                 "worst_time_error_fraction": involved})
    with open(path, "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=list(rows[0]))
        writer.writeheader()
        writer.writerows(rows)
    if plot_path:
        plot_corrections(plot_path, rows)


def plot_corrections(path, rows):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(7, 0.35 * len(rows) + 1.2))
    y = np.arange(len(rows))
    ax.barh(y, [r["fraction_of_motion"] for r in rows], color="tab:blue", label="effect")
    ax.plot([r["worst_time_error_fraction"] for r in rows], y, "k|", markersize=12, label="worst time error")
    ax.set_yticks(y, [r["correction"] for r in rows], fontsize=7)
    ax.invert_yaxis()
    ax.set_xscale("log")
    ax.set_xlabel("largest RMS displacement from the published model / largest RMS motion")
    ax.legend(fontsize=7)
    ax.grid(alpha=0.3, axis="x")
    runs.save_figure(fig, path)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--published", required=True)
    parser.add_argument("--run", action="append", required=True)
    parser.add_argument("--reference", required=True)
    parser.add_argument("--dt", type=float, default=1e-3)
    parser.add_argument("--out", required=True)
    parser.add_argument("--plot")
    parser.add_argument("--compat-reference")
    parser.add_argument("--corrections")
    parser.add_argument("--corrections-plot")
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
    if args.compat_reference and args.compat_reference not in labs:
        runs.fail(f"--compat-reference {args.compat_reference}: not among the --run labels")
    if args.corrections and not args.compat_reference:
        runs.fail("--corrections needs --compat-reference")
    compat = labs[args.compat_reference][0] if args.compat_reference else None
    rows, curves, worst_error = [], [], {}
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
            **({"fraction_of_motion_from_published_compat": float(distances(frames, compat, steps).max()) / motion}
               if compat is not None else {}),
            "time_error_mean_rms_m": te.get("mean_rms_m", ""),
            "time_error_worst_rms_fraction": float(err.max()) / motion if err is not None else "",
            "largest_rms_motion_m": motion,
        })
        curves.append((label, d, err))
        worst_error[label] = float(err.max()) / motion if err is not None else float("nan")
    with open(args.out, "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=list(rows[0]))
        writer.writeheader()
        writer.writerows(rows)
    if args.plot:
        plot(args.plot, steps, args.dt, curves, motion)
    if args.corrections:
        write_corrections(args.corrections, labs, steps, args.reference, args.compat_reference, motion, worst_error,
                          args.corrections_plot)
    print(json.dumps(rows, indent=1))


if __name__ == "__main__":
    main()
