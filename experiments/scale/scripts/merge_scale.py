#!/usr/bin/python3
"""Merges the scale study's cells (experiments/scale/about.md) into three tables:
every cell (scale.csv), the amg route against the gmres route at each size
(ratios.csv) and where the bytes go at the largest size (breakdown.csv).

Each cell is the CSV row `weavelab_bench --scale` printed (file <size>_<solver>.csv)
beside the `/usr/bin/time -v` report of its process (<size>_<solver>.time);
--runs lists the reports of whole runs as <size>_<solver>=PATH. A cell the
CPU limit stopped (SIGXCPU: an empty CSV, the report saying so) is a row with
its status, the CPU time and peak it reached, and no step figures."""
import argparse
import csv
import os
import re
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "common"))
from runs import fail  # noqa: E402

REFERENCE, OTHER = "gmres", "amg"


def max_rss_mb(path):
    """The 'Maximum resident set size (kbytes)' of a /usr/bin/time -v report [MB]."""
    with open(path) as f:
        match = re.search(r"Maximum resident set size \(kbytes\): (\d+)", f.read())
    if not match:
        fail(f"{path}: no 'Maximum resident set size' line (not a /usr/bin/time -v report?)")
    return int(match.group(1)) * 1024 / 1e6


def cpu_s(path):
    """User + system CPU time of a /usr/bin/time -v report [s]."""
    with open(path) as f:
        text = f.read()
    times = [re.search(rf"{kind} time \(seconds\): ([0-9.]+)", text) for kind in ("User", "System")]
    if not all(times):
        fail(f"{path}: no 'User time' or 'System time' line (not a /usr/bin/time -v report?)")
    return sum(float(t.group(1)) for t in times)


def stopped_by_cpu_limit(path):
    """Whether the report says the command ended on SIGXCPU (the cell's CPU limit)."""
    with open(path) as f:
        return "Command terminated by signal 24" in f.read()


def read_cell(path):
    name = os.path.basename(path)[:-len(".csv")]
    size, _, solver = name.partition("_")
    report = path[:-len(".csv")] + ".time"
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows and stopped_by_cpu_limit(report):
        return {"size": size, "solver": solver, "status": f"stopped by the CPU limit after {cpu_s(report):.0f} s CPU",
                "max_rss_mb": f"{max_rss_mb(report):.1f}"}
    if len(rows) != 1:
        fail(f"{path}: expected one row from weavelab_bench --scale, got {len(rows)}")
    row = dict(rows[0], size=size, solver=solver, status="ok")
    row["max_rss_mb"] = f"{max_rss_mb(report):.1f}"
    row["bytes_per_dof"] = f"{float(row['peak_mb']) * 1e6 / int(row['dofs']):.0f}"
    return row


def write_csv(path, rows, columns):
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=columns, extrasaction="ignore")
        w.writeheader()
        w.writerows(rows)


def label_order(label):
    """Woven sizes by size, then the other labels (the knitted cloth)."""
    return (0, int(label), "") if label.isdigit() else (1, 0, label)


def ratios(cells):
    by = {(c["size"], c["solver"]): c for c in cells if c["status"] == "ok"}
    out = []
    for size in sorted({c["size"] for c in cells}, key=label_order):
        ref, other = by.get((size, REFERENCE)), by.get((size, OTHER))
        if not ref or not other:
            continue
        out.append({"size": size, "dofs": ref["dofs"],
                    f"{REFERENCE}_step_ms": ref["step_ms"], f"{OTHER}_step_ms": other["step_ms"],
                    "step_ratio": f"{float(other['step_ms']) / float(ref['step_ms']):.3f}",
                    f"{REFERENCE}_step_cpu_ms": ref["step_cpu_ms"], f"{OTHER}_step_cpu_ms": other["step_cpu_ms"],
                    "step_cpu_ratio": f"{float(other['step_cpu_ms']) / float(ref['step_cpu_ms']):.3f}",
                    f"{REFERENCE}_peak_mb": ref["peak_mb"], f"{OTHER}_peak_mb": other["peak_mb"],
                    "peak_ratio": f"{float(other['peak_mb']) / float(ref['peak_mb']):.3f}",
                    f"{REFERENCE}_krylov": ref["krylov_per_step"], f"{OTHER}_krylov": other["krylov_per_step"]})
    return out


def breakdown(cells, runs):
    """The largest woven size's peak split by stage, one column per solver [MB]."""
    measured = [c for c in cells if c["status"] == "ok"]
    largest = max(int(c["size"]) for c in measured if c["size"].isdigit())
    chosen = [c for c in measured if c["size"] == str(largest)]
    f = lambda c, k: float(c[k])  # noqa: E731
    parts = [
        ("process at start (program and libraries)", lambda c: f(c, "rss_start_mb")),
        ("transient while building the model (above what it holds after)",
         lambda c: f(c, "peak_model_mb") - f(c, "rss_model_mb")),
        ("model built: stencils, pattern, per-term caches", lambda c: f(c, "rss_model_mb") - f(c, "rss_start_mb")),
        ("  of the model: assembly scatter plans (per element a 4-byte column start per DoF, "
         "a 2-byte row place per block entry; from the stencils)", lambda c: f(c, "scatter_plans_mb")),
        ("  of the model: sparsity pattern (8-byte values, 4-byte indices; the step matrix A is one more)",
         lambda c: f(c, "pattern_mb")),
        ("integrator initialized: step matrices, evaluation buffers",
         lambda c: f(c, "rss_initialized_mb") - f(c, "rss_model_mb")),
        ("steps done: preconditioner, Krylov bases, solver copies",
         lambda c: f(c, "rss_end_mb") - f(c, "rss_initialized_mb")),
        ("peak above the state after the steps (model build, factorization or AMG setup)",
         lambda c: f(c, "peak_mb") - f(c, "rss_end_mb")),
        ("peak resident size of the step (getrusage)", lambda c: f(c, "peak_mb")),
        ("  counted by the solver: its copies of the matrix", lambda c: f(c, "solver_matrices_mb")),
        ("  counted by the solver: factor L or AMG hierarchy", lambda c: f(c, "preconditioner_mb")),
        ("  counted by the solver: GMRES Krylov bases", lambda c: f(c, "krylov_mb")),
    ]
    rows = [{"part": name, **{c["solver"]: f"{value(c):.1f}" for c in chosen}} for name, value in parts]
    run_peaks = {solver: max_rss_mb(path) for (size, solver), path in runs.items() if size == str(largest)}
    if run_peaks:
        rows.append({"part": "peak of a whole run (weavelab run, /usr/bin/time -v)",
                     **{s: f"{v:.1f}" for s, v in run_peaks.items()}})
        rows.append({"part": "run beyond the step: frames, series, output buffers",
                     **{c["solver"]: f"{run_peaks[c['solver']] - f(c, 'max_rss_mb'):.1f}"
                        for c in chosen if c["solver"] in run_peaks}})
    return [dict(r, size=f"{largest}×{largest}") for r in rows], ["size", "part"] + [c["solver"] for c in chosen]


def estimates(cells, runs):
    """Per cell: the step's peak, the whole run's (where measured) and what weavelab run estimates [MB]."""
    out = []
    for c in cells:
        if c["status"] != "ok" or "estimate_mb" not in c:
            continue
        run = runs.get((c["size"], c["solver"]))
        run_peak = max_rss_mb(run) if run else None
        highest = max(float(c["max_rss_mb"]), run_peak or 0.0)
        out.append({"size": c["size"], "solver": c["solver"], "dofs": c["dofs"], "step_peak_mb": c["max_rss_mb"],
                    "run_peak_mb": f"{run_peak:.1f}" if run_peak else "",
                    "estimate_mb": c["estimate_mb"],
                    "estimate_over_peak": f"{float(c['estimate_mb']) / highest:.3f}",
                    "peak_bytes_per_dof": f"{highest * 1e6 / int(c['dofs']):.0f}"})
    return out


def main():
    p = argparse.ArgumentParser(description=__doc__)
    p.add_argument("--table", required=True)
    p.add_argument("--ratios", required=True)
    p.add_argument("--breakdown", required=True)
    p.add_argument("--estimates", required=True)
    p.add_argument("--cells", nargs="+", required=True)
    p.add_argument("--runs", nargs="*", default=[])
    a = p.parse_args()
    cells = sorted((read_cell(path) for path in a.cells), key=lambda c: (label_order(c["size"]), c["solver"]))
    runs = {}
    for item in a.runs:
        key, _, path = item.partition("=")
        size, _, solver = key.partition("_")
        if not path:
            fail(f"--runs: got '{item}', expected SIZE_SOLVER=PATH")
        runs[(size, solver)] = path
    columns = ["size", "solver", "status", "requested", "dofs", "nnz", "steps", "step_ms", "step_cpu_ms", "krylov_per_step",
               "factorizations_per_step", "rss_start_mb", "peak_model_mb", "rss_model_mb", "rss_initialized_mb", "rss_end_mb",
               "peak_mb", "max_rss_mb", "solver_matrices_mb", "preconditioner_mb", "krylov_mb", "scatter_plans_mb",
               "pattern_mb", "estimate_mb",
               "bytes_per_dof",
               "scene"]
    write_csv(a.table, cells, columns)
    r = ratios(cells)
    write_csv(a.ratios, r, list(r[0].keys()) if r else ["size"])
    rows, cols = breakdown(cells, runs)
    write_csv(a.breakdown, rows, cols)
    write_csv(a.estimates, estimates(cells, runs), ["size", "solver", "dofs", "step_peak_mb", "run_peak_mb",
                                                   "estimate_mb", "estimate_over_peak", "peak_bytes_per_dof"])


if __name__ == "__main__":
    main()
