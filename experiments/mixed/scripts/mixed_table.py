#!/usr/bin/python3
"""The runs of the mixed study against the first (the yarn level), frame by
frame: the RMS distance between the crossings (mean over the frames after
t = 0, in μm and as a percentage of the cloth's side), each run's own time
error (summary.json "time_error", from `weavelab run --error-estimate`) and
its CPU time (summary.json "statistics" "cpu_s") with its ratio to the yarn
level's.

    mixed_table.py YARN_RUN RUN ... --table CSV --summary CSV

--table gets one row per run; --summary one row: the smallest distance (as a
percentage of the side) among the mixed runs that took at most a third of the
yarn level's CPU time, or a sentence saying that none did.
Missing or malformed inputs: a message on stderr and exit status 2.
"""
import csv
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "common"))
import runs as wio  # noqa: E402


def time_error_m(run, summary):
    te = summary.get("time_error")
    if not isinstance(te, dict) or "mean_rms_m" not in te:
        raise wio.RunError(f"{run}: summary.json has no time_error (run it with --error-estimate)")
    return te["mean_rms_m"]


def cpu_s(run, summary):
    stats = summary.get("statistics")
    if not isinstance(stats, dict) or "cpu_s" not in stats:
        raise wio.RunError(f"{run}: summary.json has no statistics.cpu_s")
    return stats["cpu_s"]


def mean_distance_m(run, frames, reference):
    if len(frames) != len(reference):
        raise wio.RunError(f"{run} has {len(frames)} frames, the yarn level {len(reference)}")
    rms = []
    for (t, mesh), (t_ref, ref) in zip(frames, reference):
        if abs(t - t_ref) > 1e-12 or mesh.points.shape != ref.points.shape:
            raise wio.RunError(f"{run}: frame at {t} s does not match the yarn level's ({t_ref} s)")
        if t > 0:
            rms.append(np.sqrt(np.mean(np.sum((mesh.points - ref.points) ** 2, axis=1))))
    return float(np.mean(rms))


def side_m(frames):
    first = frames[0][1].points
    return float(np.max(np.ptp(first, axis=0)))


def main():
    args = sys.argv[1:]
    try:
        table = args[args.index("--table") + 1]
        summary_path = args[args.index("--summary") + 1]
    except (ValueError, IndexError):
        wio.fail("usage: mixed_table.py YARN_RUN RUN ... --table CSV --summary CSV")
    runs = [a for i, a in enumerate(args) if a not in ("--table", "--summary") and args[i - 1] not in
            ("--table", "--summary")]
    if len(runs) < 2:
        wio.fail("mixed_table.py: expected the yarn run and at least one other")
    try:
        reference = wio.read_frames(runs[0])
        side = side_m(reference)
        rows = []
        for run in runs:
            summary = wio.read_summary(run, required=True)
            frames = reference if run == runs[0] else wio.read_frames(run)
            model = summary.get("model", {})
            rows.append({"run": os.path.basename(os.path.normpath(run)), "model": model.get("name", "?"),
                         "yarn_cells": model.get("yarn_cells", "all" if model.get("name") == "yarn" else "none"),
                         "dofs": model.get("dofs", "?"), "cpu_s": cpu_s(run, summary),
                         "mean_rms_distance_um": 1e6 * mean_distance_m(run, frames, reference),
                         "time_error_um": 1e6 * time_error_m(run, summary)})
    except wio.RunError as e:
        wio.fail(str(e))
    yarn_cpu = rows[0]["cpu_s"]
    for r in rows:
        r["cpu_over_yarn"] = r["cpu_s"] / yarn_cpu
        r["distance_percent_of_side"] = 100 * 1e-6 * r["mean_rms_distance_um"] / side
    columns = ["run", "model", "yarn_cells", "dofs", "cpu_s", "cpu_over_yarn", "mean_rms_distance_um",
               "distance_percent_of_side", "time_error_um"]
    with open(table, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=columns)
        w.writeheader()
        w.writerows(rows)
    cheap = [r["distance_percent_of_side"] for r in rows if r["model"] == "mixed" and r["cpu_over_yarn"] <= 1 / 3]
    with open(summary_path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["best_within_third_cpu_percent"])
        w.writerow([f"{min(cheap):.3g} % of the cloth's side RMS apart (mean over frames)" if cheap else
                    "none costs that little here"])


if __name__ == "__main__":
    main()
