#!/usr/bin/python3
"""The accuracy study's tables from its run folders.

    accuracy_tables.py --out DIR --reference RUN --search RUN --search-exit FILE --single RUN
                       --search-benchmark TSV --single-benchmark TSV --ladder RUN...

ladder.csv: each ladder run (sdirk2 at one rtol, with --error-estimate): its
CPU time, Richardson's estimate, the bound --accuracy uses (its distance to the
ladder run ten times looser), its true error (distance to the reference) and
each estimate over the true error. trials.csv: the search's trials as its
summary records them. summary.csv: the search's verdict, chosen rtol, bound and
true error, and its wall and CPU time against one run at the chosen rtol.
Distances are means over the frames after t = 0 of the RMS over nodes (paired
by index), frames paired by time. Missing or malformed inputs: exit 2.
"""
import argparse
import csv
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "common"))
import runs as wio  # noqa: E402


def positions(run):
    """{time rounded to 1e-9 s: node positions} of the frames after t = 0."""
    return {round(t, 9): np.asarray(m.points) for t, m in wio.read_frames(run) if t > 0}


def distance(a, b):
    times = sorted(set(a) & set(b))
    if not times or len(times) != len(a) or a[times[0]].shape != b[times[0]].shape:
        wio.fail(f"runs with different frames or nodes ({len(a)} and {len(b)} frames)")
    return float(np.mean([np.sqrt(np.mean(np.sum((a[t] - b[t]) ** 2, axis=1))) for t in times]))


def benchmark(path):
    with open(path, encoding="utf-8") as f:
        row = next(csv.DictReader(f, delimiter="\t"))
    return float(row["s"]), float(row["cpu_time"])


def write_csv(path, header, rows):
    with open(path, "w", newline="", encoding="utf-8") as f:
        w = csv.writer(f)
        w.writerow(header)
        w.writerows(rows)


def ladder_rows(ladder, reference):
    runs = sorted(((wio.read_summary(r, required=True)["integrator"]["rtol"], r) for r in ladder), reverse=True)
    frames = {r: positions(r) for _, r in runs}
    rows = []
    for k, (rtol, run) in enumerate(runs):
        s = wio.read_summary(run, required=True)
        true = distance(frames[run], reference)
        richardson = s.get("time_error", {}).get("mean_rms_m", float("nan"))
        looser = runs[k - 1] if k > 0 and runs[k - 1][0] >= 10 * rtol * (1 - 1e-9) else None
        bound = distance(frames[looser[1]], frames[run]) if looser else float("nan")
        rows.append([rtol, s["statistics"]["cpu_s"], richardson, bound, true, richardson / true, bound / true])
    return rows


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    for option in ("--out", "--reference", "--search", "--search-exit", "--single", "--search-benchmark",
                   "--single-benchmark"):
        p.add_argument(option, required=True)
    p.add_argument("--ladder", nargs="+", required=True)
    a = p.parse_args()
    reference = positions(a.reference)
    write_csv(os.path.join(a.out, "ladder.csv"),
              ["rtol", "run_cpu_s", "richardson_m", "bound_from_10x_looser_m", "true_m", "richardson_over_true",
               "bound_over_true"], ladder_rows(a.ladder, reference))

    summary = wio.read_summary(a.search, required=True)
    acc = summary.get("accuracy")
    if acc is None:
        wio.fail(f"{a.search}/summary.json: no 'accuracy' record")
    write_csv(os.path.join(a.out, "trials.csv"), ["trial", "rtol", "outcome", "cpu_s", "measured_error_m"],
              [[k + 1, t["rtol"], t["outcome"], t["cpu_s"], t["estimate_mean_rms_m"]]
               for k, t in enumerate(acc["trials"])])

    bound = summary.get("time_error", {}).get("mean_rms_m", float("nan"))
    true = distance(positions(a.search), reference)
    search_wall, search_cpu = benchmark(a.search_benchmark)
    single_wall, single_cpu = benchmark(a.single_benchmark)
    with open(a.search_exit, encoding="utf-8") as f:
        exit_code = f.read().strip()
    ratio = search_cpu / single_cpu
    rows = [["target_m", acc["target_m"]], ["verdict", acc["verdict"]], ["exit_code", exit_code],
            ["trials", len(acc["trials"])], ["chosen_rtol", acc["rtol"]], ["bound_m", bound],
            ["true_error_m", true], ["search_wall_s", search_wall], ["search_cpu_s", search_cpu],
            ["single_run_wall_s", single_wall], ["single_run_cpu_s", single_cpu], ["cpu_ratio", ratio],
            ["headline", f"{acc['verdict']} at rtol {acc['rtol']:.3g}, bound {bound:.3g} m, true {true:.3g} m, "
                         f"{ratio:.2f}x the CPU of one run at that rtol"]]
    write_csv(os.path.join(a.out, "summary.csv"), ["quantity", "value"], rows)


if __name__ == "__main__":
    main()
