#!/usr/bin/python3
"""Peak memory and CPU time of building a cloth's model (`weavelab info SCENE`:
the model built, its pattern and assembly plans, nothing stepped), for this
build and optionally a reference build (an earlier revision's program), runs
interleaved (this, reference; repeat after repeat) so that the machine's load
falls alike on both. Each run under /usr/bin/time -v; medians over the repeats
and the ratio this / reference. The two builds must describe the same model
(the info lines equal), else it fails.

    build_memory.py --weavelab build/weavelab [--reference OTHER/weavelab]
                    --model yarn --repeats 3 --csv OUT.csv SIZE=SCENE ..."""
import argparse
import csv
import os
import re
import statistics
import subprocess
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "common"))
from runs import fail  # noqa: E402


def measure(program, scene, model):
    """(info text, peak resident size [MB], user + system CPU [s]) of one `info` run."""
    proc = subprocess.run(["/usr/bin/time", "-v", program, "info", scene, "--model", model],
                          capture_output=True, text=True)
    if proc.returncode != 0:
        fail(f"{program} info {scene} --model {model}: exit {proc.returncode}: {proc.stderr.strip()[-400:]}")
    rss = re.search(r"Maximum resident set size \(kbytes\): (\d+)", proc.stderr)
    user = re.search(r"User time \(seconds\): ([0-9.]+)", proc.stderr)
    system = re.search(r"System time \(seconds\): ([0-9.]+)", proc.stderr)
    if not (rss and user and system):
        fail(f"{program} info {scene}: no /usr/bin/time -v report on stderr")
    return proc.stdout, int(rss.group(1)) * 1024 / 1e6, float(user.group(1)) + float(system.group(1))


def info_value(text, key):
    match = re.search(rf"^{key}: (\S+)", text, re.MULTILINE)
    if not match:
        fail(f"weavelab info printed no '{key}:' line")
    return match.group(1)


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--weavelab", required=True)
    p.add_argument("--reference", default="", help="an earlier build's weavelab (default: none)")
    p.add_argument("--model", default="yarn")
    p.add_argument("--repeats", type=int, default=3)
    p.add_argument("--csv", required=True)
    p.add_argument("scenes", nargs="+", help="SIZE=SCENE")
    a = p.parse_args()
    if a.repeats < 1:
        fail(f"--repeats: got {a.repeats}, expected at least 1")
    builds = [("this", a.weavelab)] + ([("reference", a.reference)] if a.reference else [])
    rows = []
    for item in a.scenes:
        size, _, scene = item.partition("=")
        if not scene:
            fail(f"got '{item}', expected SIZE=SCENE")
        peaks = {name: [] for name, _ in builds}
        cpus = {name: [] for name, _ in builds}
        texts = {}
        for _ in range(a.repeats):
            for name, program in builds:
                text, peak, cpu = measure(program, scene, a.model)
                texts[name] = text
                peaks[name].append(peak)
                cpus[name].append(cpu)
        if a.reference and texts["this"] != texts["reference"]:
            fail(f"{scene}: this build and the reference describe different models:\n{texts['this']}\n"
                 f"{texts['reference']}")
        row = {"size": size, "dofs": info_value(texts["this"], "dofs"),
               "nnz": info_value(texts["this"], "matrix_nonzeros"), "repeats": a.repeats}
        for name, _ in builds:
            row[f"{name}_peak_mb"] = f"{statistics.median(peaks[name]):.1f}"
            row[f"{name}_cpu_s"] = f"{statistics.median(cpus[name]):.3g}"
        if a.reference:
            row["peak_ratio"] = f"{float(row['this_peak_mb']) / float(row['reference_peak_mb']):.3f}"
            row["cpu_ratio"] = f"{float(row['this_cpu_s']) / float(row['reference_cpu_s']):.3f}"
        row["bytes_per_dof"] = f"{float(row['this_peak_mb']) * 1e6 / int(row['dofs']):.0f}"
        rows.append(row)
    with open(a.csv + ".tmp", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)
    os.replace(a.csv + ".tmp", a.csv)


if __name__ == "__main__":
    main()
