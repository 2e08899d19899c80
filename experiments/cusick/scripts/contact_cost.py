#!/usr/bin/python3
"""The cost of contact of the Cusick drape (experiments/cusick/, docs/models.md
§3.11): per scene and model, the drape's first steps on the pedestal against the
same scene without it, each run alone: the mean wall and CPU time per step
(summary.json's totals over its steps), the median step wall time (metrics.csv),
each as a ratio to the free fall's, and the step matrix solver's work
(factorizations, GMRES iterations, the solver's name).

    contact_cost.py --runs SCENE:MODEL:DRAPE_RUN:FREE_RUN [...] --out CSV

Writes one row per scene, model and run (drape, free).
Missing or malformed inputs: a message on stderr and exit status 2.
"""
import argparse
import csv
import os
import statistics
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "common"))
import runs as io  # noqa: E402

HEADER = ["scene", "model", "run", "steps", "mean_wall_per_step_ms", "mean_cpu_per_step_ms", "median_step_wall_ms",
          "ratio_mean_wall", "ratio_mean_cpu", "ratio_median_wall", "factorizations", "gmres_iterations",
          "linear_solver"]


def measures(run):
    """(steps, mean wall [s], mean CPU [s], median step wall [s], statistics) of one run."""
    stats = io.read_summary(run, required=True).get("statistics")
    if not isinstance(stats, dict) or not stats.get("steps"):
        raise io.RunError(f"{run}: summary.json has no statistics with steps")
    steps = stats["steps"]
    median = statistics.median(io.step_wall_times(io.read_metrics(run), run))
    return steps, stats["wall_s"] / steps, stats["cpu_s"] / steps, median, stats


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--runs", nargs="+", required=True, metavar="SCENE:MODEL:DRAPE_RUN:FREE_RUN")
    ap.add_argument("--out", required=True)
    a = ap.parse_args()
    rows = []
    for item in a.runs:
        parts = item.split(":")
        if len(parts) != 4:
            raise io.RunError(f"--runs '{item}': expected SCENE:MODEL:DRAPE_RUN:FREE_RUN")
        scene, model, drape, free = parts
        free_m = measures(free)
        for name, run in (("free", free), ("drape", drape)):
            steps, wall, cpu, median, stats = measures(run) if name == "drape" else free_m
            rows.append([scene, model, name, steps, f"{1e3 * wall:.5g}", f"{1e3 * cpu:.5g}", f"{1e3 * median:.5g}",
                         f"{wall / free_m[1]:.3g}", f"{cpu / free_m[2]:.3g}", f"{median / free_m[3]:.3g}",
                         stats.get("factorizations", ""), stats.get("krylov_iters", ""),
                         str(stats.get("linear_solver", "")).split(" (")[0]])
    with open(a.out, "w", newline="", encoding="utf-8") as f:
        w = csv.writer(f, lineterminator="\n")
        w.writerow(HEADER)
        w.writerows(rows)


if __name__ == "__main__":
    try:
        main()
    except io.RunError as e:
        io.fail(str(e))
