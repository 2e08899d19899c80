#!/usr/bin/python3
"""Summary of the published code's linear solves: solver.csv (step, relative_residual) -> one row.

    summarize_solver.py SOLVER_CSV OUT_CSV

Columns: steps, median and largest relative residual ||A v1 - b|| / ||b||, and how many steps
left a residual above 1e-6 (a solve that far from its system is not the backward Euler step).
Exit 2 on a missing or malformed file.
"""
import csv
import statistics
import sys


def main():
    if len(sys.argv) != 3:
        print(__doc__, file=sys.stderr)
        sys.exit(2)
    try:
        with open(sys.argv[1], newline="") as f:
            residuals = [float(r["relative_residual"]) for r in csv.DictReader(f)]
    except (OSError, KeyError, ValueError) as e:
        print(f"summarize_solver.py: error: {sys.argv[1]}: {e}", file=sys.stderr)
        sys.exit(2)
    if not residuals:
        print(f"summarize_solver.py: error: {sys.argv[1]} holds no step", file=sys.stderr)
        sys.exit(2)
    with open(sys.argv[2], "w", newline="") as f:
        writer = csv.writer(f)
        writer.writerow(["steps", "median_relative_residual", "largest_relative_residual", "steps_above_1e-6"])
        writer.writerow([len(residuals), statistics.median(residuals), max(residuals),
                         sum(r > 1e-6 for r in residuals)])


if __name__ == "__main__":
    main()
