#!/usr/bin/python3
"""The validation table and chart of the calibration study's dynamic part
(experiments/calibration/Snakefile): for each scene and continuum (first
guess, static fit, dynamic fit, static fit with the yarn level's node masses,
that with its shear raised by the config's shear_factor, and the spline shear
law without and with those masses), the mean and
worst per-frame RMS distance to the yarn level beside both runs' estimated
time errors (summary.json "time_error", docs/models.md §7.8), and the
distance against time.

    validation_table.py DIR SCENE=YARN_RUN ...

reads DIR/distance_<kind>_<scene>.csv (experiments/common/compare.py) and the
continuum runs DIR/fem_<kind>_<scene>; writes DIR/summary.csv, DIR/summary.md
and DIR/validation.png (.svg). Missing inputs: a message and exit 2.
"""
import csv
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "common"))
import runs as wio  # noqa: E402

KINDS = [("first_guess", "first guess (hinges)"), ("static", "static fit (grid lines)"),
         ("dynamic", "dynamic fit (grid lines)"), ("yarnmass", "static fit, yarn node mass"),
         ("shear_scaled", "yarn node mass, shear scaled"), ("spline", "spline shear (grid lines)"),
         ("spline_mass", "spline shear, yarn node mass")]


def mean_time_error(run):
    te = (wio.read_summary(run, required=True) or {}).get("time_error") or {}
    return float(te["mean_rms_m"]) if "mean_rms_m" in te else float("nan")


def read_distance(path):
    if not os.path.isfile(path):
        raise wio.RunError(f"{path}: missing (run experiments/common/compare.py first)")
    with open(path, newline="") as f:
        rows = [(float(r["time_s"]), float(r["rms_distance_m"]), float(r["max_distance_m"]))
                for r in csv.DictReader(f)]
    return [r for r in rows if r[0] > 0]  # frames after t = 0, as compare.py's budget


def verdict(distance, errors):
    worst = max(errors)
    if np.isnan(worst):
        return "time error not estimated"
    if worst > distance:
        return "time error exceeds the distance"
    if worst > 0.1 * distance:
        return "time error above a tenth of the distance"
    return "resolved"


def main():
    if len(sys.argv) < 3 or any("=" not in a for a in sys.argv[2:]):
        wio.fail(__doc__.strip().split("\n\n")[1].strip())
    out = sys.argv[1]
    scenes = [a.split("=", 1) for a in sys.argv[2:]]
    rows, curves = [], {}
    try:
        for scene, yarn in scenes:
            yarn_error = mean_time_error(yarn)
            for kind, _ in KINDS:
                d = read_distance(os.path.join(out, f"distance_{kind}_{scene}.csv"))
                fem_error = mean_time_error(os.path.join(out, f"fem_{kind}_{scene}"))
                mean = float(np.mean([r[1] for r in d]))
                rows.append({"scene": scene, "continuum": kind, "mean_rms_m": mean,
                             "worst_frame_rms_m": max(r[1] for r in d), "max_m": max(r[2] for r in d),
                             "yarn_time_error_m": yarn_error, "continuum_time_error_m": fem_error,
                             "verdict": verdict(mean, [yarn_error, fem_error])})
                curves[(scene, kind)] = d
    except wio.RunError as e:
        wio.fail(str(e))

    text = [",".join(rows[0].keys())]
    text += [",".join(f"{v:.6g}" if isinstance(v, float) else v for v in r.values()) for r in rows]
    wio.write_text_atomically(os.path.join(out, "summary.csv"), "\n".join(text) + "\n")
    md = ["| scene | " + " | ".join(label for _, label in KINDS) + " | time error: yarn / continuum |",
          "|---|" + "---|" * len(KINDS) + "---|"]
    for scene, _ in scenes:
        mine = [r for r in rows if r["scene"] == scene]
        cells = [f"{1e3 * r['mean_rms_m']:.2f} mm" for r in mine]
        errors = "{:.3f} / {} mm".format(1e3 * mine[0]["yarn_time_error_m"],
                                         " – ".join(f"{1e3 * r['continuum_time_error_m']:.3f}" for r in mine))
        md.append(f"| `{scene}` | " + " | ".join(cells) + f" | {errors} |")
    wio.write_text_atomically(os.path.join(out, "summary.md"), "\n".join(md) + "\n")

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, len(scenes), figsize=(3.2 * len(scenes), 3.2), sharey=True, squeeze=False)
    for ax, (scene, yarn) in zip(axes[0], scenes):
        for kind, label in KINDS:
            d = curves[(scene, kind)]
            ax.plot([r[0] for r in d], [1e3 * r[1] for r in d], label=label)
        ax.axhline(1e3 * mean_time_error(yarn), color="grey", linestyle=":", label="yarn level's time error (mean)")
        ax.set_title(scene, fontsize=9)
        ax.set_xlabel("time [s]")
        ax.grid(alpha=0.3)
    axes[0][0].set_ylabel("RMS distance to the yarn level [mm]")
    axes[0][0].legend(fontsize=7)
    fig.tight_layout()
    print("\n".join(wio.save_figure(fig, os.path.join(out, "validation.png"))))
    print("\n".join(md))


if __name__ == "__main__":
    main()
