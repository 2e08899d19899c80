#!/usr/bin/python3
"""Tension of one frame, in the material plane and in 3-D, side by side.

    plot_tension.py RUN [--frame K] --out PNG

Triangles (and line cells, if they carry it) are coloured by the cell data
"tension" in N/m; a multi-component tension is shown by its Euclidean norm.
The left view places each point at its material coordinates (point data "uv",
or "u" and "v"); the right view shows the deformed cloth. K indexes the
frames of the run's .pvd (default: the last; negative counts from the end).
When a few cells carry far more than the rest (e.g. at the handles), the
colour scale ends at the 98th percentile and the colour bar says so.
Missing or malformed inputs: a message on stderr and exit status 2.
"""
import argparse
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import runs as wio  # noqa: E402

CLIP_PERCENTILE = 98.0  # colour scale end when a few cells dominate (see plot())


def tension_cells(mesh, label):
    """(triangles, their tension, lines, their tension, scalar label)."""
    if "tension" not in mesh.cell_data:
        raise wio.RunError(f"{label}: no cell data 'tension' (present: {', '.join(mesh.cell_data) or 'none'})")
    tri, t_tri = wio.cells_with_data(mesh, "triangle", "tension", label)
    lines, t_lines = wio.cells_with_data(mesh, "line", "tension", label)
    if len(tri) == 0 and len(lines) == 0:
        raise wio.RunError(f"{label}: no triangle or line cells to colour")
    norm = any(np.asarray(t).ndim > 1 and np.asarray(t).shape[1] > 1 for t in (t_tri, t_lines))
    scalar = (lambda t: np.linalg.norm(t.reshape(len(t), -1), axis=1)) if norm else (lambda t: t.reshape(-1))
    return tri, scalar(t_tri), lines, scalar(t_lines), ("|tension|" if norm else "tension")


def plot(run, frame_index, out):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.collections import LineCollection, PolyCollection
    from mpl_toolkits.mplot3d.art3d import Line3DCollection, Poly3DCollection

    entries = wio.read_pvd(wio.find_pvd(run))
    if not entries:
        raise wio.RunError(f"run '{run}' has no frames")
    if not -len(entries) <= frame_index < len(entries):
        raise wio.RunError(f"--frame {frame_index} is out of range: run '{run}' has {len(entries)} frames "
                           f"(0..{len(entries) - 1})")
    time, path = entries[frame_index]
    mesh = wio.read_mesh(path)
    label = f"{run} frame {frame_index % len(entries)}"
    tri, t_tri, lines, t_lines, what = tension_cells(mesh, label)
    uv = 1e3 * wio.material_coordinates(mesh, label)  # drawn in mm
    x = 1e3 * np.asarray(mesh.points, float)[:, :3]
    values = np.concatenate([t_tri, t_lines])
    finite = values[np.isfinite(values)]
    vmin, vmax = (float(finite.min()), float(finite.max())) if len(finite) else (0.0, 1.0)
    # A few faces at the handles can carry far more than the rest: the colour
    # scale then ends at the 98th percentile (the colour bar says so).
    clip = float(np.percentile(finite, CLIP_PERCENTILE)) if len(finite) else vmax
    clipped = clip > vmin and vmax - vmin > 2.0 * (clip - vmin)
    true_max = vmax
    if clipped:
        vmax = clip
    if vmin == vmax:
        vmin, vmax = vmin - 0.5, vmax + 0.5
    cmap = plt.get_cmap("viridis")
    norm = matplotlib.colors.Normalize(vmin=vmin, vmax=vmax)

    fig = plt.figure(figsize=(12, 5.2))
    ax2 = fig.add_subplot(1, 2, 1)
    ax3 = fig.add_subplot(1, 2, 2, projection="3d")
    if len(tri):
        ax2.add_collection(PolyCollection(uv[tri], array=t_tri, cmap=cmap, norm=norm, edgecolors="face"))
        ax3.add_collection3d(Poly3DCollection(x[tri], facecolors=cmap(norm(t_tri)), edgecolors="none"))
    if len(lines):
        ax2.add_collection(LineCollection(uv[lines], array=t_lines, cmap=cmap, norm=norm, linewidths=1.5))
        ax3.add_collection3d(Line3DCollection(x[lines], colors=cmap(norm(t_lines)), linewidths=1.5))
    ax2.set_xlim(uv[:, 0].min(), uv[:, 0].max())
    ax2.set_ylim(uv[:, 1].min(), uv[:, 1].max())
    ax2.set_aspect("equal")
    ax2.invert_yaxis()  # v (row j) grows downward, as in the upright pose
    ax2.set_xlabel("material u, warp (mm)")
    ax2.set_ylabel("material v, weft (mm)")
    ax2.set_title("material plane (u, v)")
    lo, hi = x.min(axis=0), x.max(axis=0)
    centre, half = (lo + hi) / 2, max(float((hi - lo).max()) / 2, 1e-12)
    ax3.set_xlim(centre[0] - half, centre[0] + half)
    ax3.set_ylim(centre[1] - half, centre[1] + half)
    ax3.set_zlim(centre[2] - half, centre[2] + half)
    for axis in (ax3.xaxis, ax3.yaxis, ax3.zaxis):
        axis.set_major_locator(matplotlib.ticker.MaxNLocator(5))
    ax3.set_xlabel("x (mm)", labelpad=6)
    ax3.set_ylabel("y (mm)", labelpad=6)
    ax3.set_zlabel("z (mm)", labelpad=6)
    ax3.tick_params(labelsize="small")
    ax3.set_title("deformed (3-D)")
    bar = fig.colorbar(matplotlib.cm.ScalarMappable(norm=norm, cmap=cmap), ax=[ax2, ax3], shrink=0.85, pad=0.06,
                       extend="max" if clipped else "neither")
    bar.set_label(f"{what} (N/m)" + (f"\nscale ends at the {CLIP_PERCENTILE:g}th percentile; max {true_max:.3g}"
                                      if clipped else ""))
    fig.suptitle(f"Tension map: {wio.run_label(run)}, t = {time:.6g} s")
    written = wio.save_figure(fig, out, svg=False)
    plt.close(fig)
    return written


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("run", metavar="RUN", help="run folder")
    parser.add_argument("--frame", type=int, default=-1, metavar="K", help="frame index (default: last)")
    parser.add_argument("--out", required=True, metavar="PNG", help="image to write")
    args = parser.parse_args(argv)
    try:
        written = plot(args.run, args.frame, args.out)
    except wio.RunError as e:
        wio.fail(str(e))
    print(f"wrote {', '.join(written)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
