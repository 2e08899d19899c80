"""The homogenization study's tables and figure from one `weavelab tiles` folder.

usage: tile_tables.py CELL SAMPLING_CSV ERRORS_CSV FIGURE_PNG

CELL holds tiles.json and held_out.csv (the held-out samples beside the law).
SAMPLING_CSV: the tile, the number of samples and converged ones, the sampling
wall and CPU time. ERRORS_CSV: the law's relative RMS errors on the fitted and
the held-out samples (energy and each stress). FIGURE_PNG: the held-out
samples' energy and warp moment against the law's.
"""
import csv
import json
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "common"))
from runs import fail, save_figure  # noqa: E402

NAMES = ["stretch_warp", "stretch_weft", "shear", "curvature_warp", "curvature_weft", "twist"]


def main(argv):
    if len(argv) != 5:
        fail(__doc__)
    cell, sampling_csv, errors_csv, figure = argv[1:5]
    with open(os.path.join(cell, "tiles.json")) as f:
        summary = json.load(f)
    with open(sampling_csv, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["tile", "samples", "converged", "sampling_wall_s", "sampling_cpu_s", "samples_file"])
        w.writerow([summary["tile"], summary["samples"], summary["converged"], summary.get("sampling_wall_s", ""),
                    summary.get("sampling_cpu_s", ""), summary["samples_file"]])
    law_json = summary["law"]
    with open(errors_csv, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["samples", "count", "energy"] + [f"stress_{n}" for n in NAMES] + ["stress_max"])
        for part in ("fitted", "held_out"):
            e = law_json[part]
            w.writerow([part, e["samples"], e["energy_relative_rms"]]
                       + [e["stress_relative_rms"][n] for n in NAMES] + [e["stress_relative_rms_max"]])
    with open(os.path.join(cell, "held_out.csv"), newline="") as f:
        held = list(csv.DictReader(f))
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 2, figsize=(9, 4.3))
    panels = [("W_J_per_m2", "law_W_J_per_m2", "energy density W [J/m²]"),
              ("dW_dcurvature_warp", "law_dW_dcurvature_warp", "warp moment ∂W/∂κ_u [N]")]
    for ax, (sample_key, law_key, label) in zip(axes, panels):
        xs = [float(r[sample_key]) for r in held]
        ys = [float(r[law_key]) for r in held]
        ax.plot(xs, ys, ".", ms=3)
        lim = [min(xs + ys), max(xs + ys)]
        ax.plot(lim, lim, "k-", lw=0.7)
        ax.set_xlabel(f"tile: {label}")
        ax.set_ylabel(f"law: {label}")
    fig.suptitle(f"{summary['tile']} tile, {len(held)} held-out samples")
    fig.tight_layout()
    save_figure(fig, figure)


if __name__ == "__main__":
    main(sys.argv)
