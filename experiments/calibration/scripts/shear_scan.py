#!/usr/bin/python3
"""The trajectory cost along the shear stiffness alone: one row per scan run.

    shear_scan.py OUT_CSV TARGET_RUN SECONDS FACTOR=RUN,DISTANCE_CSV ...

For each factor: the RMS over the frames in (0, SECONDS] of the per-frame RMS
distance to the target (DISTANCE_CSV, experiments/common/compare.py), beside
the scan run's and the target's estimated time errors (summary.json
"time_error", mean RMS; docs/models.md §7.8). Writes OUT_CSV with the columns
shear_factor, rms_over_fitted_frames_m, continuum_time_error_m,
target_time_error_m. Missing inputs: a message, exit 2, nothing written.
"""
import csv
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "common"))
import runs as wio  # noqa: E402


def mean_time_error(run):
    te = (wio.read_summary(run, required=True) or {}).get("time_error") or {}
    if "mean_rms_m" not in te:
        raise wio.RunError(f"{run}/summary.json: no time_error.mean_rms_m (run it with --error-estimate)")
    return float(te["mean_rms_m"])


def rms_over(path, seconds):
    try:
        with open(path, newline="", encoding="utf-8") as f:
            d = [float(r["rms_distance_m"]) for r in csv.DictReader(f) if 0 < float(r["time_s"]) <= seconds + 1e-9]
    except OSError as e:
        raise wio.RunError(f"{path}: {e.strerror}") from None
    if not d:
        raise wio.RunError(f"{path}: no frame in (0, {seconds}] s")
    return math.sqrt(sum(x * x for x in d) / len(d))


def main(argv):
    if len(argv) < 4:
        wio.fail(__doc__.strip().split("\n\n")[1].strip())
    out, target, seconds_text, entries = argv[0], argv[1], argv[2], argv[3:]
    try:
        seconds = float(seconds_text)
    except ValueError:
        wio.fail(f"SECONDS: got '{seconds_text}', expected a number")
    lines = ["shear_factor,rms_over_fitted_frames_m,continuum_time_error_m,target_time_error_m"]
    try:
        target_error = mean_time_error(target)
        for entry in entries:
            factor, sep, paths = entry.partition("=")
            run, comma, distance = paths.partition(",")
            if not sep or not comma:
                wio.fail(f"'{entry}': expected FACTOR=RUN,DISTANCE_CSV")
            lines.append(f"{factor},{rms_over(distance, seconds):.6g},{mean_time_error(run):.3g},{target_error:.3g}")
    except wio.RunError as e:
        wio.fail(str(e))
    wio.write_text_atomically(out, "\n".join(lines) + "\n")


if __name__ == "__main__":
    main(sys.argv[1:])
