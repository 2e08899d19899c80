#!/usr/bin/python3
"""The error-budget table: runs against a converged reference, with their estimates.

    error_budget.py OUT REFERENCE LABEL=RUN ...

For each run folder RUN, named LABEL in the table: its CPU time and steps
(summary.json), its true time error (the distance to REFERENCE, nodes paired by
index, experiments/common/compare.py) and its estimated time error
(summary.json "time_error", docs/models.md §7.8), each as the mean over frames
after t = 0 of the RMS over nodes, over the first half of the duration, the
second half and the whole. Writes OUT/error_budget.csv,
OUT/error_budget.md and OUT/error_budget.png/.svg. A run that did not end ok is
listed with its outcome. Missing inputs: a message on stderr and exit status 2.
"""
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "common"))
import compare  # noqa: E402
import runs as wio  # noqa: E402


def window_means(times, values, half):
    times, values = np.asarray(times), np.asarray(values)
    keep = times > 0
    first, second = keep & (times <= half + 1e-12), times > half + 1e-12
    return [float(values[m].mean()) if m.any() else float("nan") for m in (first, second, keep)]


def measure(label, run, reference):
    summary = wio.read_summary(run, required=True)
    stats, result = summary["statistics"], summary["result"]
    row = {"run": label, "outcome": result["outcome"],
           "integrator": summary["integrator"]["name"], "cpu_s": stats["cpu_s"], "steps": stats["steps"]}
    if result["outcome"] != "ok":
        return row
    rows, _, _ = compare.compare(run, reference)
    duration = max(r[0] for r in rows)
    row["true"] = window_means([r[0] for r in rows], [r[1] for r in rows], duration / 2)
    te = summary.get("time_error") or {}
    if "rms_m" in te:
        row["estimate"] = window_means(te["times_s"], te["rms_m"], duration / 2)
        row["estimate_cpu_s"] = te["second_run_cpu_s"]
        row["method"] = te["method"]
    return row


def mm(x):
    return "–" if x is None or not np.isfinite(x) else f"{1e3 * x:.3f}"


def main(argv):
    if len(argv) < 3 or any("=" not in a for a in argv[2:]):
        wio.fail(__doc__.split("\n\n")[1].strip())
    out, reference, runs = argv[0], argv[1], [a.split("=", 1) for a in argv[2:]]
    try:
        rows = [measure(label, run, reference) for label, run in runs]
    except wio.RunError as e:
        wio.fail(str(e))
    head = ["run", "outcome", "cpu_s", "steps", "true_first_half_m", "true_second_half_m", "true_all_m",
            "estimate_first_half_m", "estimate_second_half_m", "estimate_all_m", "estimate_method", "estimate_cpu_s"]
    lines = [",".join(head)]
    md = ["| run | CPU s | steps | true time error, mm: 1st half / 2nd half / all | estimated, mm: all | "
          "estimated / true |", "|---|---|---|---|---|---|"]
    for r in rows:
        true, est = r.get("true", [float("nan")] * 3), r.get("estimate", [float("nan")] * 3)
        lines.append(",".join([r["run"], r["outcome"], repr(r["cpu_s"]), str(r["steps"])] + [repr(x) for x in true + est]
                              + [r.get("method", ""), repr(r.get("estimate_cpu_s", float("nan")))]))
        if r["outcome"] != "ok":
            md.append(f"| {r['run']} | {r['cpu_s']:.1f} | {r['steps']} | {r['outcome']} | – | – |")
            continue
        ratio = est[2] / true[2] if np.isfinite(est[2]) and true[2] > 0 else float("nan")
        md.append(f"| {r['run']} | {r['cpu_s']:.1f} | {r['steps']} | {mm(true[0])} / {mm(true[1])} / {mm(true[2])} | "
                  f"{mm(est[2])} | {ratio:.2f} |")
    wio.write_text_atomically(os.path.join(out, "error_budget.csv"), "\n".join(lines) + "\n")
    wio.write_text_atomically(os.path.join(out, "error_budget.md"), "\n".join(md) + "\n")
    print("\n".join(md))

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    ok = [r for r in rows if "true" in r]
    fig, (left, right) = plt.subplots(1, 2, figsize=(12, 5))
    for r in ok:
        colour = "#e377c2" if r["integrator"] == "sdirk2" else "#1f77b4"
        right.loglog(r["cpu_s"], 1e3 * r["true"][2], "o", color=colour)
        right.annotate(r["run"], (r["cpu_s"], 1e3 * r["true"][2]), textcoords="offset points", xytext=(4, 4),
                       fontsize=7)
        if "estimate" in r:
            left.loglog(1e3 * r["true"][2], 1e3 * r["estimate"][2], "o", color=colour)
            left.annotate(r["run"], (1e3 * r["true"][2], 1e3 * r["estimate"][2]), textcoords="offset points",
                          xytext=(4, 4), fontsize=7)
    lo, hi = left.get_xlim()
    left.plot([lo, hi], [lo, hi], "k-", lw=0.8, label="estimate = true")
    left.plot([lo, hi], [2 * lo, 2 * hi], "k:", lw=0.8, label="×2")
    left.plot([lo, hi], [lo / 2, hi / 2], "k:", lw=0.8)
    left.set_xlabel("true time error, mean RMS [mm]")
    left.set_ylabel("estimated time error [mm]")
    left.legend(fontsize=8)
    right.set_xlabel("CPU time [s]")
    right.set_ylabel("true time error, mean RMS [mm]")
    for ax in (left, right):
        ax.grid(True, which="both", alpha=0.3)
    fig.suptitle("Time error against a converged reference (IDA, rtol 1e-8); blue be-linear, pink sdirk2",
                 fontsize=10)
    fig.tight_layout()
    wio.save_figure(fig, os.path.join(out, "error_budget.png"), svg=True)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
