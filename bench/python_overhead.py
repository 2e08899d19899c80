"""Cost of a run driven from Python against the same run from the command line
(README, "Scripting from Python"): `weavelab run SCENE --duration D` as a
process against weavelab.run(scene, duration=D) in this process, both writing
their folder, and weavelab.run without writing; interleaved, REPEATS each, one
thread (OMP_NUM_THREADS=1, OPENBLAS_NUM_THREADS=1) on both sides. Measures wall
time and CPU time (user + system: the child's for the command line, process
time for the module) and prints every run, the medians and their ratios.

    PYTHONPATH=build/python /usr/bin/python3 bench/python_overhead.py \
        [SCENE] [DURATION] [REPEATS]
"""
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

root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
scene_path = sys.argv[1] if len(sys.argv) > 1 else os.path.join(root, "experiments", "scenes", "hanging_wind.toml")
duration = float(sys.argv[2]) if len(sys.argv) > 2 else 0.1
repeats = int(sys.argv[3]) if len(sys.argv) > 3 else 5
cli = os.environ.get("WEAVELAB_CLI", os.path.join(root, "build", "weavelab"))

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
