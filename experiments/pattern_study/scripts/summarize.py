#!/usr/bin/python3
"""Table and chart of the pattern study: the fitted continuum parameters of each
fabric (calibration.json from `weavelab calibrate`) against the weave pattern.
Usage: summarize.py OUT_DIR CALIBRATION_JSON...
Writes OUT_DIR/parameters.csv, parameters.md, parameters.png and .svg.
"""
import csv
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

KEYS = ["warp_stretch_N_per_m", "weft_stretch_N_per_m", "shear_N_per_m", "shear_lock_angle_rad",
        "shear_lock_exponent", "warp_bending_N_m", "weft_bending_N_m"]


def main(out, files):
    rows = []
    for f in files:
        fabric = os.path.basename(os.path.dirname(f))
        pattern, pair = fabric.split("_")
        d = json.load(open(f))
        p = {e["key"]: e for e in d["parameters"]}
        worst = max(t["residual_rms_relative"] for t in d["tests"])
        row = {"fabric": fabric, "pattern": pattern, "yarns": f"({pair[0]},{pair[1]})", "worst_residual": worst}
        for k in KEYS:
            row[k] = p[k]["value"] if k in p else float("nan")
            row[k + "_std"] = p[k]["std_error"] if k in p and p[k]["std_error"] is not None else float("nan")
        rows.append(row)
    cols = list(rows[0].keys())
    with open(os.path.join(out, "parameters.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=cols)
        w.writeheader()
        w.writerows(rows)
    with open(os.path.join(out, "parameters.md"), "w") as f:
        f.write("| fabric | warp stretch N/m | weft stretch N/m | shear N/m | lock angle rad | lock exp. | "
                "warp bending N·m | weft bending N·m | worst residual |\n|---|---|---|---|---|---|---|---|---|\n")
        for r in rows:
            f.write(f"| {r['pattern']}-{r['yarns']} | {r['warp_stretch_N_per_m']:.4g} | {r['weft_stretch_N_per_m']:.4g} | "
                    f"{r['shear_N_per_m']:.4g} | {r['shear_lock_angle_rad']:.3g} | {r['shear_lock_exponent']:.3g} | "
                    f"{r['warp_bending_N_m']:.3g} | {r['weft_bending_N_m']:.3g} | {100 * r['worst_residual']:.2g} % |\n")
    fig, axes = plt.subplots(1, 4, figsize=(16, 3.6))
    pairs = sorted({r["yarns"] for r in rows})
    patterns = ["plain", "twill", "satin"]
    for ax, (key, label) in zip(axes, [("warp_stretch_N_per_m", "warp stretch [N/m]"), ("shear_N_per_m", "shear [N/m]"),
                                       ("shear_lock_angle_rad", "shear lock angle [rad]"),
                                       ("warp_bending_N_m", "warp bending [N·m]")]):
        for i, pair in enumerate(pairs):
            xs, ys, es = [], [], []
            for j, pat in enumerate(patterns):
                for r in rows:
                    if r["pattern"] == pat and r["yarns"] == pair:
                        xs.append(j + 0.1 * (i - 1))
                        ys.append(r[key])
                        es.append(r[key + "_std"])
            ax.errorbar(xs, ys, yerr=es, fmt="o", label=f"yarns {pair}")
        ax.set_xticks(range(len(patterns)), patterns)
        ax.set_title(label)
        ax.grid(alpha=0.3)
    axes[0].legend(fontsize=8)
    fig.tight_layout()
    for ext in ("png", "svg"):
        fig.savefig(os.path.join(out, f"parameters.{ext}"), dpi=110)


if __name__ == "__main__":
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2:])
