#!/usr/bin/python3
"""The scale probe of the knits study (experiments/knits/): per run, the DoFs
(and the knit's stitch contacts) that `weavelab info` states, the median step
wall time (metrics.csv), the peak resident memory (the Snakemake benchmark's
max_rss), both per DoF, and each as a ratio to the reference run's per DoF.

    scale_table.py --run NAME:INFO:RUN:BENCHMARK [...] --reference NAME --out CSV

Missing or malformed inputs: a message on stderr and exit status 2.
"""
import argparse
import csv
import os
import re
import statistics
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "common"))
import runs as io  # noqa: E402


def read_text(path):
    try:
        with open(path, encoding="utf-8") as f:
            return f.read()
    except OSError as e:
        raise io.RunError(f"cannot read '{path}': {e}") from e


def peak_rss_mb(benchmark):
    rows = list(csv.DictReader(read_text(benchmark).splitlines(), delimiter="\t"))
    if not rows or "max_rss" not in rows[0]:
        raise io.RunError(f"'{benchmark}': no max_rss (a Snakemake benchmark file)")
    return float(rows[0]["max_rss"])


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--run", action="append", required=True, metavar="NAME:INFO:RUN:BENCHMARK")
    ap.add_argument("--reference", required=True)
    ap.add_argument("--out", required=True)
    a = ap.parse_args()
    rows = {}
    for item in a.run:
        parts = item.split(":")
        if len(parts) != 4:
            raise io.RunError(f"--run '{item}': expected NAME:INFO:RUN:BENCHMARK")
        name, info_path, run, benchmark = parts
        info = dict(re.findall(r"^(\w+): (.*)$", read_text(info_path), re.M))
        if "dofs" not in info:
            raise io.RunError(f"'{info_path}': no 'dofs:' line (the output of `weavelab info`)")
        dofs = int(info["dofs"])
        wall = io.step_wall_times(io.read_metrics(run), run)
        rows[name] = dict(run=name, dofs=dofs, stitch_contacts=info.get("stitch_contacts", ""), steps=len(wall),
                          median_step_s=statistics.median(wall), peak_rss_MB=peak_rss_mb(benchmark))
    if a.reference not in rows:
        raise io.RunError(f"--reference {a.reference}: not one of {', '.join(rows)}")
    ref = rows[a.reference]
    header = ["run", "dofs", "stitch_contacts", "steps", "median_step_s", "step_us_per_dof", "peak_rss_MB",
              "rss_kB_per_dof", "step_per_dof_vs_reference", "rss_per_dof_vs_reference"]
    with open(a.out, "w", newline="", encoding="utf-8") as f:
        w = csv.writer(f, lineterminator="\n")
        w.writerow(header)
        for r in rows.values():
            w.writerow([r["run"], r["dofs"], r["stitch_contacts"], r["steps"], f"{r['median_step_s']:.4g}",
                        f"{1e6 * r['median_step_s'] / r['dofs']:.4g}", f"{r['peak_rss_MB']:.4g}",
                        f"{1024 * r['peak_rss_MB'] / r['dofs']:.4g}",
                        f"{(r['median_step_s'] / r['dofs']) / (ref['median_step_s'] / ref['dofs']):.3g}",
                        f"{(r['peak_rss_MB'] / r['dofs']) / (ref['peak_rss_MB'] / ref['dofs']):.3g}"])


if __name__ == "__main__":
    try:
        main()
    except io.RunError as e:
        io.fail(str(e))
