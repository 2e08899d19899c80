"""Cost of a run driven from Python against the same run from the command line
(README, "Scripting from Python"): `weavelab run SCENE --duration D` as a
process against weavelab.run(scene, duration=D) in this process, both writing
their folder, and weavelab.run without writing; interleaved, REPEATS each, one
thread (OMP_NUM_THREADS=1, OPENBLAS_NUM_THREADS=1) on both sides. Prints every
wall time, the medians and their ratios.

    PYTHONPATH=build/python /usr/bin/python3 experiments/bench/python_overhead.py \
        [SCENE] [DURATION] [REPEATS]
"""
import os
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

times = {"cli": [], "python_out": [], "python_memory": []}
with tempfile.TemporaryDirectory() as tmp:
    for k in range(repeats):
        start = time.perf_counter()
        subprocess.run([cli, "run", scene_path, "--duration", str(duration), "--quiet", "--out",
                        os.path.join(tmp, "cli")], check=True)
        times["cli"].append(time.perf_counter() - start)

        start = time.perf_counter()
        run = weavelab.run(scene_path, duration=duration, out=os.path.join(tmp, "python"))
        times["python_out"].append(time.perf_counter() - start)
        assert run.outcome == "ok", run.message

        start = time.perf_counter()
        run = weavelab.run(scene_path, duration=duration)
        times["python_memory"].append(time.perf_counter() - start)
        print(f"round {k + 1}: " + ", ".join(f"{name} {t[-1]:.3f} s" for name, t in times.items()), flush=True)

median = {name: statistics.median(t) for name, t in times.items()}
steps = run.summary["statistics"]["steps"]
print(f"{os.path.basename(scene_path)}, {duration} s ({steps} steps), {repeats} interleaved runs each, medians: "
      + ", ".join(f"{name} {m:.3f} s" for name, m in median.items()))
print(f"ratio python_out / cli = {median['python_out'] / median['cli']:.3f}; "
      f"python_memory / cli = {median['python_memory'] / median['cli']:.3f}")
