#!/usr/bin/python3
"""The scale study's figure: median step time (wall, and the process's CPU
time: the machine may be shared) and resident size (the peak, and what is held
after the steps) against the DoFs of the
woven cloth, one line per step solver (log-log); cells the CPU limit stopped
are left out. Usage: plot_scale.py scale.csv out.png"""
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "common"))
from runs import save_figure  # noqa: E402


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    with open(sys.argv[1], newline="") as f:
        rows = [r for r in csv.DictReader(f) if r["size"].isdigit() and r["status"] == "ok"]
    fig, (ax_t, ax_m) = plt.subplots(1, 2, figsize=(10, 4))
    for solver in sorted({r["solver"] for r in rows}):
        mine = sorted((r for r in rows if r["solver"] == solver), key=lambda r: int(r["dofs"]))
        dofs = [int(r["dofs"]) for r in mine]
        line, = ax_t.loglog(dofs, [float(r["step_ms"]) / 1e3 for r in mine], "o-", label=f"{solver} (wall)")
        ax_t.loglog(dofs, [float(r["step_cpu_ms"]) / 1e3 for r in mine], "s--", color=line.get_color(),
                    label=f"{solver} (CPU)")
        ax_m.loglog(dofs, [float(r["peak_mb"]) / 1e3 for r in mine], "o-", color=line.get_color(),
                    label=f"{solver} (peak)")
        ax_m.loglog(dofs, [float(r["rss_end_mb"]) / 1e3 for r in mine], "s--", color=line.get_color(),
                    label=f"{solver} (held after the steps)")
    ax_t.set(xlabel="DoFs (woven cloth)", ylabel="median be-linear step [s]", title="time per step")
    ax_m.set(xlabel="DoFs (woven cloth)", ylabel="resident size [GB]", title="memory")
    for ax in (ax_t, ax_m):
        ax.grid(True, which="both", alpha=0.3)
        ax.legend()
    fig.tight_layout()
    save_figure(fig, sys.argv[2])


if __name__ == "__main__":
    main()
