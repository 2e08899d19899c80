"""Cost of a run driven from Python against the same run from the command line
(README, "Scripting from Python"): `weavelab run SCENE --duration D` as a
process against weavelab.run(scene, duration=D) in this process, both writing
their folder, and weavelab.run without writing; interleaved, REPEATS each, one
thread (OMP_NUM_THREADS=1, OPENBLAS_NUM_THREADS=1) on both sides. Measures wall
time and CPU time (user + system: the child's for the command line, process
time for the module) and prints every run, the medians and their ratios.

    PYTHONPATH=build/python /usr/bin/python3 experiments/speed/scripts/python_overhead.py \
        [--scene SCENE] [--duration D] [--repeats N] [--weavelab PROGRAM] [--csv OUT]

The CSV has one row per kind (cli, python_out, python_memory): median wall and
CPU time [s] and their ratios to the command line's.
"""
import argparse
import csv
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time

os.environ["OMP_NUM_THREADS"] = "1"  # before the module loads OpenMP
os.environ["OPENBLAS_NUM_THREADS"] = "1"
import weavelab  # noqa: E402

root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))
parser = argparse.ArgumentParser(description="Cost of a run driven from Python against the command line.")
parser.add_argument("--scene", default=os.path.join(root, "experiments", "scenes", "hanging_wind.toml"))
parser.add_argument("--duration", type=float, default=0.1, help="simulated time [s]")
parser.add_argument("--repeats", type=int, default=5, help="interleaved runs of each kind")
parser.add_argument("--weavelab", default=os.path.join(root, "build", "weavelab"), help="the program")
parser.add_argument("--csv", help="write the medians and ratios here")
args = parser.parse_args()
if args.repeats < 1 or not args.duration > 0:
    parser.error(f"--repeats {args.repeats} --duration {args.duration}: expected a positive count and time")
scene_path, duration, repeats, cli = args.scene, args.duration, args.repeats, args.weavelab


def child_cpu():
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def timed(kind, call):
    """Wall and CPU seconds of call(); the CPU of a child process for "cli"."""
    cpu = child_cpu if kind == "cli" else time.process_time
    w0, c0 = time.perf_counter(), cpu()
    result = call()
    return time.perf_counter() - w0, cpu() - c0, result


names = ("cli", "python_out", "python_memory")
wall = {n: [] for n in names}
cpu = {n: [] for n in names}
with tempfile.TemporaryDirectory() as tmp:
    calls = {
        "cli": lambda: subprocess.run([cli, "run", scene_path, "--duration", str(duration), "--quiet", "--out",
                                       os.path.join(tmp, "cli")], check=True),
        "python_out": lambda: weavelab.run(scene_path, duration=duration, out=os.path.join(tmp, "python")),
        "python_memory": lambda: weavelab.run(scene_path, duration=duration),
    }
    for k in range(repeats):
        for n in names:
            w, c, result = timed(n, calls[n])
            assert n == "cli" or result.outcome == "ok", result.message
            if n != "cli":
                run = result
            wall[n].append(w)
            cpu[n].append(c)
        print(f"round {k + 1}: " + ", ".join(f"{n} {wall[n][-1]:.3f} s wall / {cpu[n][-1]:.3f} s CPU" for n in names),
              flush=True)

steps = run.summary["statistics"]["steps"]
print(f"{os.path.basename(scene_path)}, {duration} s ({steps} steps), {repeats} interleaved runs each")
for label, t in (("wall", wall), ("CPU", cpu)):
    m = {n: statistics.median(t[n]) for n in names}
    print(f"median {label}: " + ", ".join(f"{n} {m[n]:.3f} s" for n in names) +
          f"; python_out / cli = {m['python_out'] / m['cli']:.3f}, python_memory / cli = "
          f"{m['python_memory'] / m['cli']:.3f}")

if args.csv:
    with open(args.csv + ".tmp", "w", newline="", encoding="utf-8") as f:
        w = csv.writer(f, lineterminator="\n")
        w.writerow(["kind", "scene", "duration_s", "steps", "repeats", "median_wall_s", "median_cpu_s",
                    "wall_over_cli", "cpu_over_cli"])
        mw = {n: statistics.median(wall[n]) for n in names}
        mc = {n: statistics.median(cpu[n]) for n in names}
        for n in names:
            w.writerow([n, os.path.basename(scene_path), duration, steps, repeats, f"{mw[n]:.6g}", f"{mc[n]:.6g}",
                        f"{mw[n] / mw['cli']:.4f}", f"{mc[n] / mc['cli']:.4f}"])
    os.replace(args.csv + ".tmp", args.csv)
