#!/usr/bin/python3
"""Compares run folders of `weavelab run` byte for byte with the first one:
every frame file (frames/*.vtu) and metrics.csv without its wall-time columns
(those whose name contains "wall", which measure the machine, not the run).

Usage: compare_runs.py OUT_CSV SUMMARY_CSV SETTING=RUN_DIR...
Writes OUT_CSV (one row per run: setting, files compared, files differing,
verdict) and SUMMARY_CSV (runs, reruns, identical reruns).
"""
import csv
import glob
import os
import sys


def fail(message):
    print(f"compare_runs.py: error: {message}", file=sys.stderr)
    sys.exit(2)


def metrics_without_wall(folder):
    path = os.path.join(folder, "metrics.csv")
    if not os.path.isfile(path):
        fail(f"'{path}' is missing (did the run end?)")
    with open(path, newline="", encoding="utf-8") as f:
        rows = list(csv.reader(f))
    if not rows:
        fail(f"'{path}' is empty")
    keep = [i for i, name in enumerate(rows[0]) if "wall" not in name]
    return "\n".join(",".join(row[i] for i in keep) for row in rows).encode()


def frames(folder):
    names = sorted(os.path.relpath(p, folder) for p in glob.glob(os.path.join(folder, "frames", "*.vtu")))
    if not names:
        fail(f"'{folder}/frames' holds no .vtu frame")
    return names


def read_bytes(path):
    with open(path, "rb") as f:
        return f.read()


def compare(reference, folder):
    """(files compared, files differing) of `folder` against `reference`."""
    names = frames(reference)
    differing = sum(1 for n in names
                    if not os.path.isfile(os.path.join(folder, n))
                    or read_bytes(os.path.join(folder, n)) != read_bytes(os.path.join(reference, n)))
    differing += len(set(frames(folder)) - set(names))
    differing += metrics_without_wall(folder) != metrics_without_wall(reference)
    return len(names) + 1, differing


def summary(rows):
    """Counts of the reruns bitwise identical to the first, in all and per OpenBLAS setting, and a sentence."""
    reruns = rows[1:]
    groups = {}
    for r in reruns:
        groups.setdefault(r["OPENBLAS_NUM_THREADS"], []).append(r["files_differing"] == 0)
    parts = [f"{sum(same)} of {len(same)} with OPENBLAS_NUM_THREADS "
             + ("unset" if blas == "default" else f"= {blas}") for blas, same in groups.items()]
    identical = sum(1 for r in reruns if r["files_differing"] == 0)
    return {"runs": len(rows), "reruns": len(reruns), "identical_reruns": identical,
            "summary": f"{identical} of {len(reruns)} reruns bitwise identical to the first: " + ", ".join(parts)}


def main(argv):
    if len(argv) < 4 or any("=" not in a for a in argv[2:]):
        fail("usage: compare_runs.py OUT_CSV SUMMARY_CSV SETTING=RUN_DIR...")
    runs = [a.split("=", 1) for a in argv[2:]]
    rows = []
    reference = runs[0][1]
    for k, (setting, folder) in enumerate(runs):
        omp, blas = setting.split("_")
        if k == 0:
            compared, differing, verdict = len(frames(folder)) + 1, 0, "reference"
        else:
            compared, differing = compare(reference, folder)
            verdict = "bitwise identical" if differing == 0 else f"{differing} files differ"
        rows.append({"run": k, "OMP_NUM_THREADS": omp, "OPENBLAS_NUM_THREADS": blas, "files_compared": compared,
                     "files_differing": differing, "verdict": verdict})
    for path, table in ((argv[0], rows), (argv[1], [summary(rows)])):
        with open(path + ".tmp", "w", newline="", encoding="utf-8") as f:
            w = csv.DictWriter(f, fieldnames=list(table[0]), lineterminator="\n")
            w.writeheader()
            w.writerows(table)
        os.replace(path + ".tmp", path)


if __name__ == "__main__":
    main(sys.argv[1:])
