#!/usr/bin/env python3
"""The knit patches at their last frame in 3-D (the knits study's curl part, experiments/knits/;
docs/models.md §11). Usage: render_knits.py OUT.png SCENE:RUN [SCENE:RUN ...]

One panel per run: its last frame's yarn segments (the frame's line cells,
coloured by course) drawn as lines whose width follows the yarn's diameter
against the panel's span (roughly, as matplotlib draws 3-D lines), in the
cloth's own frame (x along the course, y along the wale, z towards the face)
with equal axes, seen from the front and above."""
import os
import sys
import tomllib

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "common"))
import runs as io  # noqa: E402


def main():
    if len(sys.argv) < 3:
        io.fail(__doc__)
    out, panels = sys.argv[1], []
    for arg in sys.argv[2:]:
        scene_path, run = arg.split(":", 1)
        with open(scene_path, "rb") as f:
            scene = tomllib.load(f)
        frames = io.read_frames(run)
        if not frames:
            io.fail(f"{run}: no frames")
        t, mesh = frames[-1]
        lines, course = io.cells_with_data(mesh, "line", "course", run)
        panels.append((scene["cloth"]["pattern"]["kind"], t, mesh.points, lines, course, scene["cloth"]["radius_m"]))
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from mpl_toolkits.mplot3d.art3d import Line3DCollection
    fig = plt.figure(figsize=(4.2 * len(panels), 4.4))
    for i, (name, t, points, lines, course, radius) in enumerate(panels):
        ax = fig.add_subplot(1, len(panels), i + 1, projection="3d")
        p = 1e3 * points
        lo, hi = p.min(axis=0), p.max(axis=0)
        span = float((hi - lo).max())
        # Line width in points: the yarn's diameter at the panel's scale (the largest span about 1.2 inches on the page).
        width = max(0.3, 2 * 1e3 * radius / span * 1.2 * 72)
        colours = plt.cm.viridis(course / max(1.0, course.max()))
        ax.add_collection3d(Line3DCollection(p[lines], colors=colours, linewidths=width))
        centre = (lo + hi) / 2
        for setter, c in zip((ax.set_xlim, ax.set_ylim, ax.set_zlim), centre):
            setter(c - span / 2, c + span / 2)
        ax.set_box_aspect((1, 1, 1))
        ax.view_init(elev=35, azim=-60)
        ax.set_xlabel("x [mm]")
        ax.set_ylabel("y [mm]")
        ax.set_zlabel("z [mm]")
        ax.set_title(f"{name}, t = {t:g} s", fontsize=9)
    io.save_figure(fig, out, svg=False)


if __name__ == "__main__":
    try:
        main()
    except io.RunError as e:
        io.fail(str(e))
