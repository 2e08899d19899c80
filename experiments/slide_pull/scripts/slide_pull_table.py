#!/usr/bin/python3
"""Two yarn-level runs of one scene that differ in a parameter (μ and 2μ on
slide_pull_7.toml), frame by frame: the RMS and largest distance between the
crossings, each run's estimated time error at that frame (summary.json
"time_error", from `weavelab run --error-estimate`) and each run's slide
indicator (point data "sliding": the largest value and how many crossing DoFs
are above 0.5).

    slide_pull_table.py RUN_A RUN_B [--summary CSV]

Prints the table (Markdown); --summary also writes the means over the frames
after t = 0 (mean_rms_distance_um, mean_time_error_a_um, mean_time_error_b_um).
Missing or malformed inputs: a message on stderr and exit status 2.
"""
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "common"))
import runs as wio  # noqa: E402


def time_errors(run, summary):
    te = summary.get("time_error") if isinstance(summary, dict) else None
    if not isinstance(te, dict) or "rms_m" not in te:
        raise wio.RunError(f"{run}: summary.json has no per-frame time_error (run it with --error-estimate)")
    return dict(zip(te["times_s"], te["rms_m"])), te["mean_rms_m"]


def main():
    args = sys.argv[1:]
    summary = None
    if len(args) == 4 and args[2] == "--summary":
        summary, args = args[3], args[:2]
    if len(args) != 2:
        wio.fail("usage: slide_pull_table.py RUN_A RUN_B [--summary CSV]")
    runs = args
    try:
        frames = [wio.read_frames(r) for r in runs]
        errors = [time_errors(r, wio.read_summary(r, required=True)) for r in runs]
        if len(frames[0]) != len(frames[1]):
            raise wio.RunError(f"{runs[0]} has {len(frames[0])} frames, {runs[1]} {len(frames[1])}")
        print("| t [ms] | distance RMS / max [μm] | time error A / B [μm] | slide max, DoFs > 0.5: A | B |")
        print("|---|---|---|---|---|")
        distances = []
        for (ta, a), (tb, b) in zip(*frames):
            if abs(ta - tb) > 1e-12:
                raise wio.RunError(f"frame times differ: {ta} s in {runs[0]}, {tb} s in {runs[1]}")
            d = np.linalg.norm(a.points - b.points, axis=1)
            rms = float(np.sqrt(np.mean(d**2)))
            slide = [wio.point_array(m, "sliding", r) for m, r in ((a, runs[0]), (b, runs[1]))]
            te = [next((v for t, v in e.items() if abs(t - ta) < 1e-12), None) for e, _ in errors]
            tes = " / ".join("–" if v is None else f"{1e6 * v:.3g}" for v in te)
            sl = [f"{s.max():.3g}, {int((s > 0.5).sum())}" for s in slide]
            if ta > 0:
                distances.append(rms)
            print(f"| {1e3 * ta:.4g} | {1e6 * rms:.3g} / {1e6 * d.max():.3g} | {tes} | {sl[0]} | {sl[1]} |")
        print(f"\nmean over frames after t = 0 of the RMS distance: {1e6 * np.mean(distances):.3g} μm; "
              f"mean time error: A {1e6 * errors[0][1]:.3g} μm, B {1e6 * errors[1][1]:.3g} μm")
        if summary:
            wio.write_text_atomically(summary, "mean_rms_distance_um,mean_time_error_a_um,mean_time_error_b_um\n"
                                      f"{1e6 * np.mean(distances):.6g},{1e6 * errors[0][1]:.6g},"
                                      f"{1e6 * errors[1][1]:.6g}\n")
    except wio.RunError as e:
        wio.fail(str(e))


if __name__ == "__main__":
    main()
