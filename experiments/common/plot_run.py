#!/usr/bin/python3
"""Energy and speed of one run over time, from its metrics.csv.

    plot_run.py RUN --out PNG [--partial]

Top: kinetic, potential and total energy (J, or mJ/µJ/nJ as the values
need); bottom: the largest node speed
(m/s). Writes PNG and an SVG beside it. --partial reads metrics.csv.part of an
interrupted run. Missing or malformed inputs: a message on stderr and exit 2.
"""
import argparse
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import runs as wio  # noqa: E402


def energy_unit(values):
    """(scale, unit) so that `values * scale` reads in J, mJ, µJ or nJ."""
    finite = np.abs(np.asarray(values, float))
    finite = finite[np.isfinite(finite)]
    top = float(finite.max()) if len(finite) else 0.0
    for scale, unit in ((1.0, "J"), (1e3, "mJ"), (1e6, "µJ"), (1e9, "nJ")):
        if top * scale >= 1.0:
            return scale, unit
    return (1e9, "nJ") if top > 0 else (1.0, "J")


def plot(run, out, partial=False):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    metrics = wio.read_metrics(run, allow_partial=partial)
    t = wio.metric(metrics, "time_s", run)
    kinetic = wio.metric(metrics, "kinetic_J", run)
    potential = wio.metric(metrics, "potential_J", run)
    speed = wio.metric(metrics, "max_speed_m_per_s", run)
    if len(t) == 0:
        raise wio.RunError(f"{run}: metrics.csv has no rows")

    fig, (ax_e, ax_v) = plt.subplots(2, 1, sharex=True, figsize=(7, 6))
    scale, unit = energy_unit(np.concatenate([kinetic, potential, kinetic + potential]))
    ax_e.plot(t, scale * kinetic, label="kinetic")
    ax_e.plot(t, scale * potential, label="potential")
    ax_e.plot(t, scale * (kinetic + potential), "k--", lw=1, label="total")
    ax_e.set_ylabel(f"energy ({unit})")
    ax_e.set_title("energy (potential of the conservative terms)", fontsize="medium")
    ax_e.grid(True, alpha=0.3)
    ax_e.legend()
    ax_v.plot(t, speed, color="C3")
    ax_v.set_ylabel("max speed (m/s)")
    ax_v.set_title("largest node speed", fontsize="medium")
    ax_v.set_xlabel("time (s)")
    ax_v.grid(True, alpha=0.3)
    title = wio.run_label(run)
    wall = wio.step_wall_times(metrics, run) if "step_wall_s" in metrics else []
    if len(wall):
        median = float(np.median(wall))
        step = f"{median:.3g} s" if median >= 1.0 else f"{median * 1e3:.3g} ms"
        title += f"\n{len(wall)} steps, median step wall time {step}"
    fig.suptitle(title)
    written = wio.save_figure(fig, out, svg=True)
    plt.close(fig)
    return written


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("run", metavar="RUN", help="run folder")
    parser.add_argument("--out", required=True, metavar="PNG", help="image to write (SVG beside it)")
    parser.add_argument("--partial", action="store_true", help="read metrics.csv.part of an interrupted run")
    args = parser.parse_args(argv)
    try:
        written = plot(args.run, args.out, args.partial)
    except wio.RunError as e:
        wio.fail(str(e))
    print(f"wrote {', '.join(written)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
