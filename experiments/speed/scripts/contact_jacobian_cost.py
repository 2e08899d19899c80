#!/usr/bin/python3
"""What time.exact_contact_jacobian costs (docs/models.md §3.6.1): a scene run
with the contact normal force F_n and friction's F_u frozen (the default) and
differentiated (`exact_contact_jacobian = true`), be-newton, alternating, RUNS
times each; the medians of the wall and CPU time (user + system of the child)
per run and their ratio exact / frozen, measured in this one run.

    experiments/speed/scripts/contact_jacobian_cost.py OUT_DIR [--scene SCENE]
        [--duration 0.05] [--runs 5] [--weavelab PROGRAM]

Writes OUT_DIR/times.csv (every run) and OUT_DIR/contact_jacobian_cost.csv
(medians and ratios).
"""
import argparse
import csv
import os
import resource
import statistics
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))


def fail(message):
    print(f"contact_jacobian_cost.py: error: {message}", file=sys.stderr)
    sys.exit(2)


def exact_scene(scene, path):
    """The scene with time.exact_contact_jacobian = true."""
    with open(scene, encoding="utf-8") as f:
        text = f.read()
    if "exact_contact_jacobian" in text:
        fail(f"{scene}: sets exact_contact_jacobian already; expected a scene that leaves it at its default")
    if "\n[time]\n" not in text:
        fail(f"{scene}: no [time] table")
    with open(path, "w", encoding="utf-8") as f:
        f.write(text.replace("\n[time]\n", "\n[time]\nexact_contact_jacobian = true\n", 1))


def child_cpu():
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def timed_run(program, scene, duration, out):
    """(wall, CPU) seconds of one `weavelab run`."""
    cmd = [program, "run", scene, "--integrator", "be-newton", "--duration", str(duration), "--quiet", "--out", out]
    w0, c0 = time.perf_counter(), child_cpu()
    p = subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    if p.returncode != 0:
        fail(f"{' '.join(cmd)} exited {p.returncode}: {p.stderr.strip()[-400:]}")
    return time.perf_counter() - w0, child_cpu() - c0


def write_csv(path, header, rows):
    with open(path + ".tmp", "w", newline="", encoding="utf-8") as f:
        w = csv.writer(f, lineterminator="\n")
        w.writerow(header)
        w.writerows(rows)
    os.replace(path + ".tmp", path)


def main():
    parser = argparse.ArgumentParser(description="The cost of time.exact_contact_jacobian.")
    parser.add_argument("out", help="output folder")
    parser.add_argument("--scene", default=os.path.join(ROOT, "experiments", "scenes", "hanging_wind.toml"))
    parser.add_argument("--duration", type=float, default=0.05, help="simulated time per run [s]")
    parser.add_argument("--runs", type=int, default=5, help="runs of each kind")
    parser.add_argument("--weavelab", default=os.path.join(ROOT, "build", "weavelab"), help="the program")
    a = parser.parse_args()
    if a.runs < 1 or not a.duration > 0:
        fail(f"--runs {a.runs} --duration {a.duration}: expected a positive count and time")
    os.makedirs(a.out, exist_ok=True)
    scenes = {"frozen": a.scene, "exact": os.path.join(a.out, "exact.toml")}
    exact_scene(a.scene, scenes["exact"])
    times = []
    for r in range(a.runs):
        for kind in ("frozen", "exact"):
            wall, cpu = timed_run(a.weavelab, scenes[kind], a.duration, os.path.join(a.out, f"run_{kind}"))
            times.append((kind, r, f"{wall:.4f}", f"{cpu:.4f}"))
    write_csv(os.path.join(a.out, "times.csv"), ["kind", "run", "wall_s", "cpu_s"], times)
    med = {k: (statistics.median(float(t[2]) for t in times if t[0] == k),
               statistics.median(float(t[3]) for t in times if t[0] == k)) for k in scenes}
    rows = [[k, a.runs, f"{med[k][0]:.4g}", f"{med[k][1]:.4g}", f"{med[k][0] / med['frozen'][0]:.3f}",
             f"{med[k][1] / med['frozen'][1]:.3f}"] for k in ("frozen", "exact")]
    write_csv(os.path.join(a.out, "contact_jacobian_cost.csv"),
              ["contact_jacobian", "runs", "median_wall_s", "median_cpu_s", "wall_over_frozen", "cpu_over_frozen"],
              rows)
    for row in rows:
        print(", ".join(map(str, row)))


if __name__ == "__main__":
    main()
