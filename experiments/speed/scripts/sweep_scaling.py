#!/usr/bin/python3
"""A sweep of independent runs on every core: the ladder run one job after
another, then again with WORKERS processes at a time; the outputs of both must
be bitwise the same (every file, without the clock and host fields of the run
summary and the step_wall_s column of metrics.csv),
and the script prints the measured speed-up and an estimate for more cores from
the per-job times of the serial pass (longest-job-first on K workers: the sum of
the jobs over K, never less than the longest job).

    experiments/speed/scripts/sweep_scaling.py [--workers 2] [--estimate 16] [--ladder error-budget|models]
        [--weavelab PROGRAM] [--csv OUT]

Ladders on the 17×17 hanging cloth, 0.05 s: error-budget, the serial loop of
the error-budget study (integrators and steps); models, yarn and FEM under
be-linear, be-newton and sdirk2. Each job runs on one thread (OMP_NUM_THREADS=1,
OPENBLAS_NUM_THREADS=1): one process per core. Exit 1 when the passes differ.
"""
import argparse
import csv
import filecmp
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time
from concurrent.futures import ThreadPoolExecutor

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))
BIN = os.path.join(ROOT, "build", "weavelab")  # --weavelab
SCENES = os.path.join(ROOT, "experiments", "scenes")

LADDERS = {
    "error-budget": [
        (label, [os.path.join(SCENES, "hanging_wind.toml"), "--duration", "0.05", *opts.split()])
        for label, opts in [
            ("be-linear-1ms", "--integrator be-linear --dt 0.001"),
            ("be-linear-0.5ms", "--integrator be-linear --dt 0.0005"),
            ("be-linear-0.25ms", "--integrator be-linear --dt 0.00025"),
            ("sdirk2-1ms", "--integrator sdirk2 --dt 0.001"),
            ("sdirk2-0.5ms", "--integrator sdirk2 --dt 0.0005"),
            ("sdirk2-rtol1e-4", "--integrator sdirk2 --rtol 1e-4"),
        ]
    ],
    "models": [
        (f"{model}-{integ}", [os.path.join(SCENES, "hanging_wind.toml"), "--model", model, "--integrator", integ,
                              "--duration", "0.05"])
        for model in ["yarn", "fem"] for integ in ["be-linear", "be-newton", "sdirk2"]
    ],
}
# Run-summary fields that differ between two identical runs (clock and host).
VOLATILE = {"wall_s", "cpu_s", "memory", "machine", "threads", "environment", "finished_utc"}


def metrics_without_clock(path):
    """metrics.csv without its step_wall_s column."""
    with open(path) as f:
        rows = [line.rstrip("\n").split(",") for line in f]
    drop = rows[0].index("step_wall_s") if rows and "step_wall_s" in rows[0] else None
    return [[c for i, c in enumerate(r) if i != drop] for r in rows]


def run(job, out):
    label, args = job
    start = time.perf_counter()
    cmd = [BIN, "run", *args, "--quiet", "--out", os.path.join(out, label)]
    p = subprocess.run(cmd, env=dict(os.environ, OMP_NUM_THREADS="1", OPENBLAS_NUM_THREADS="1"),
                       stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    if p.returncode not in (0, 1):  # 1: a numerical failure is an outcome of the ladder
        sys.exit(f"sweep_scaling: {' '.join(cmd)} exited {p.returncode}: {p.stderr.strip()[-300:]}")
    return time.perf_counter() - start


def strip(value):
    if isinstance(value, dict):
        return {k: strip(v) for k, v in value.items() if k not in VOLATILE}
    if isinstance(value, list):
        return [strip(v) for v in value]
    return value


def differences(a, b):
    """Files of run folders a and b that are not bitwise the same (summary.json without its clock fields)."""
    bad = []
    for folder, _, files in os.walk(a):
        for f in files:
            if f == ".weavelab.lock":  # the writer's lock: its process id
                continue
            pa = os.path.join(folder, f)
            pb = os.path.join(b, os.path.relpath(pa, a))
            if not os.path.exists(pb):
                bad.append(pb + " missing")
            elif f == "summary.json":
                with open(pa) as fa, open(pb) as fb:
                    if strip(json.load(fa)) != strip(json.load(fb)):
                        bad.append(pa)
            elif f == "metrics.csv":
                if metrics_without_clock(pa) != metrics_without_clock(pb):
                    bad.append(pa)
            elif not filecmp.cmp(pa, pb, shallow=False):
                bad.append(pa)
    return bad


def makespan(times, workers):
    loads = [0.0] * workers
    for t in sorted(times, reverse=True):
        loads[loads.index(min(loads))] += t
    return max(loads)


def write_row(path, row):
    with open(path + ".tmp", "w", newline="", encoding="utf-8") as f:
        w = csv.DictWriter(f, fieldnames=list(row), lineterminator="\n")
        w.writeheader()
        w.writerow(row)
    os.replace(path + ".tmp", path)


def main():
    global BIN
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--estimate", type=int, default=16)
    ap.add_argument("--ladder", choices=sorted(LADDERS), default="error-budget")
    ap.add_argument("--weavelab", default=BIN, help="the program (default build/weavelab)")
    ap.add_argument("--csv", help="write the ladder's row (times, speed-up, estimates, identical) here")
    a = ap.parse_args()
    BIN = a.weavelab
    if a.workers < 1 or a.estimate < 1:
        print("sweep_scaling: --workers and --estimate must be positive", file=sys.stderr)
        sys.exit(2)
    jobs = LADDERS[a.ladder]
    tmp = tempfile.mkdtemp(prefix="sweep_scaling_")
    try:
        serial, parallel = os.path.join(tmp, "serial"), os.path.join(tmp, "parallel")
        start = time.perf_counter()
        times = [run(j, serial) for j in jobs]
        t_serial = time.perf_counter() - start
        start = time.perf_counter()
        with ThreadPoolExecutor(a.workers) as pool:
            list(pool.map(lambda j: run(j, parallel), jobs))
        t_parallel = time.perf_counter() - start
        bad = differences(serial, parallel)
        print(f"ladder {a.ladder}: {len(jobs)} runs; per-job wall [s] (serial pass): " +
              ", ".join(f"{j[0]} {t:.2f}" for j, t in zip(jobs, times)))
        print(f"serial {t_serial:.1f} s, {a.workers} workers {t_parallel:.1f} s: speed-up {t_serial / t_parallel:.2f}")
        for k in (a.workers, a.estimate):
            print(f"estimate on {k} cores from the per-job times: {sum(times) / makespan(times, k):.2f}× "
                  f"(longest job {max(times):.2f} s of {sum(times):.2f} s)")
        print("outputs: bitwise the same as the serial pass" if not bad else "outputs DIFFER: " + ", ".join(bad))
        if a.csv:
            write_row(a.csv, {"ladder": a.ladder, "runs": len(jobs), "workers": a.workers,
                              "serial_wall_s": f"{t_serial:.4g}", "parallel_wall_s": f"{t_parallel:.4g}",
                              "speed_up": f"{t_serial / t_parallel:.3f}",
                              "longest_job_s": f"{max(times):.4g}", "estimate_cores": a.estimate,
                              "estimated_speed_up": f"{sum(times) / makespan(times, a.estimate):.3f}",
                              "bitwise_identical": "yes" if not bad else "no"})
        sys.exit(1 if bad else 0)
    finally:
        shutil.rmtree(tmp, ignore_errors=True)


if __name__ == "__main__":
    main()
