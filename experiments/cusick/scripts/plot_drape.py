#!/usr/bin/python3
"""The Cusick-style drape of the models side by side, and its measures in time.

    plot_drape.py FOLDER --out PNG [--models yarn,fem]

FOLDER holds, per model, the run drape_<model>/ and its per-frame table
drape_<model>.csv (drape_measure.py --state), as the cusick study
(experiments/cusick/Snakefile) writes them. Top: the last frame of each model in
3-D, coloured by height, with the pedestal's rim. Bottom: the drape coefficient
and the kinetic energy of the models against time.
Missing or malformed inputs: a message on stderr and exit status 2.
"""
import argparse
import csv
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "common"))
import runs as wio  # noqa: E402

LABELS = {"yarn": "yarn level", "fem": "continuum (FEM)"}


def read_csv(path):
    try:
        with open(path, newline="") as f:
            rows = list(csv.reader(f))
    except OSError as e:
        raise wio.RunError(f"cannot read '{path}': {e}") from e
    head, data = rows[0], np.array([[float(x) for x in r] for r in rows[1:]])
    if "kinetic_J" not in head:
        raise wio.RunError(f"'{path}': no kinetic_J column (drape_measure.py --state writes it)")
    return {h: data[:, k] for k, h in enumerate(head)}


def triangles(mesh):
    tris = []
    for block in mesh.cells:
        if block.type == "triangle":
            tris.extend(block.data.tolist())
        elif block.type == "quad":
            tris.extend([q[0], q[1], q[2]] for q in block.data)
            tris.extend([q[0], q[2], q[3]] for q in block.data)
    return np.array(tris)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("folder")
    ap.add_argument("--out", required=True)
    ap.add_argument("--models", default="yarn,fem", help="comma-separated models (default yarn,fem)")
    a = ap.parse_args()
    models = [(m, LABELS.get(m, m)) for m in a.models.split(",") if m]
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig = plt.figure(figsize=(11, 8))
    measures = {}
    for k, (model, label) in enumerate(models):
        t, mesh = wio.read_frames(os.path.join(a.folder, f"drape_{model}"))[-1]
        _, obstacles = wio.read_frames(os.path.join(a.folder, f"drape_{model}"), "obstacles")[-1]
        measures[model] = read_csv(os.path.join(a.folder, f"drape_{model}.csv"))
        ax = fig.add_subplot(2, len(models), k + 1, projection="3d")
        p = mesh.points
        ax.plot_trisurf(p[:, 0] * 1e3, p[:, 1] * 1e3, p[:, 2] * 1e3, triangles=triangles(mesh), cmap="viridis",
                        linewidth=0.0, antialiased=False)
        top = obstacles.points[np.isclose(obstacles.points[:, 2], obstacles.points[:, 2].max())]
        c = top[:, :2].mean(axis=0)
        r = np.linalg.norm(top[:, :2] - c, axis=1).max()
        phi = np.linspace(0.0, 2.0 * np.pi, 181)
        ax.plot((c[0] + r * np.cos(phi)) * 1e3, (c[1] + r * np.sin(phi)) * 1e3, np.full_like(phi, top[0, 2] * 1e3),
                "r-", lw=1.0)
        m = measures[model]
        ax.set_title(f"{label}, t = {t:.2f} s\ndrape coefficient {m['drape_coefficient'][-1]:.3f}, "
                     f"{int(m['folds'][-1])} folds, KE {m['kinetic_J'][-1]:.1e} J", fontsize=9)
        ax.set_xlabel("x [mm]")
        ax.set_ylabel("y [mm]")
        ax.set_zlabel("z [mm]")
        ax.set_box_aspect((1, 1, 0.6))
    ax_dc, ax_ke = fig.add_subplot(2, 2, 3), fig.add_subplot(2, 2, 4)
    for model, label in models:
        m = measures[model]
        ax_dc.plot(m["time_s"], m["drape_coefficient"], label=label)
        ax_ke.semilogy(m["time_s"], np.maximum(m["kinetic_J"], 1e-16), label=label)
    ax_ke.axhline(1e-9, color="k", ls=":", lw=0.8, label="1e-9 J")
    ax_dc.set_xlabel("time [s]")
    ax_dc.set_ylabel("drape coefficient")
    ax_ke.set_xlabel("time [s]")
    ax_ke.set_ylabel("kinetic energy [J]")
    for ax in (ax_dc, ax_ke):
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
    fig.tight_layout()
    wio.save_figure(fig, a.out, svg=False)


if __name__ == "__main__":
    try:
        main()
    except wio.RunError as e:
        print(f"plot_drape.py: {e}", file=sys.stderr)
        sys.exit(2)
