#!/usr/bin/python3
"""The icosphere mesh against the analytic sphere (experiments/obstacles/,
docs/models.md §3.11.9), per model: over the frames, the closest any node came
to each obstacle by that obstacle's own distance (‖x − c‖ − r for the sphere;
the exact point–triangle distance to the mesh as written in obstacles.pvd) and
the frames with a node inside; the median step, the steps and the rejected ones;
then the final positions' largest and RMS distance between the two runs beside
each run's estimated time error at the last frame (largest over the nodes,
summary.json "time_error", from `weavelab run --error-estimate`).

    mesh_compare.py SPHERE_SCENE --runs MODEL:SPHERE_RUN:MESH_RUN [...] --obstacles CSV --positions CSV

Missing or malformed inputs: a message on stderr and exit status 2.
"""
import argparse
import os
import statistics
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "common"))
import runs as io  # noqa: E402
from contact_cost import sphere_of, write_csv  # noqa: E402


def segment_distance(p, a, b):
    """Distance of points p (n, 3) to segments a→b (m, 3): (n, m)."""
    ab = b - a
    t = np.clip(np.einsum("nmk,mk->nm", p[:, None, :] - a[None], ab) / np.einsum("mk,mk->m", ab, ab), 0, 1)
    return np.linalg.norm(p[:, None, :] - (a[None] + t[..., None] * ab[None]), axis=2)


def mesh_distance(p, v, tri):
    """Exact distance of points p to the triangles, and whether each point is
    inside the (convex, closed) mesh: below every face plane."""
    a, b, c = v[tri[:, 0]], v[tri[:, 1]], v[tri[:, 2]]
    n = np.cross(b - a, c - a)
    n /= np.linalg.norm(n, axis=1)[:, None]
    h = np.einsum("nmk,mk->nm", p[:, None, :] - a[None], n)  # signed plane distances
    q = p[:, None, :] - h[..., None] * n[None]  # projections on the planes
    inside_tri = np.ones(h.shape, bool)
    for u, w in ((a, b), (b, c), (c, a)):
        inside_tri &= np.einsum("nmk,mk->nm", np.cross(w - u, q - u[None]), n) >= 0
    d = np.where(inside_tri, np.abs(h), np.inf)
    for u, w in ((a, b), (b, c), (c, a)):
        d = np.minimum(d, segment_distance(p, u, w))
    return d.min(axis=1), (h < 0).all(axis=1)  # the written faces point out (oriented at load)


def closest_over_frames(run, center, radius, mesh):
    """(closest distance [m], frames with a node inside, frames) of one run."""
    frames = io.read_frames(run)
    obstacle = dict(io.read_frames(run, "obstacles")) if mesh else {}
    closest, inside = np.inf, 0
    for t, m in frames:
        if mesh:
            o = obstacle[t]
            tri = next(c.data for c in o.cells if c.type == "triangle")
            d, ins = mesh_distance(m.points, o.points, tri)
        else:
            d = np.linalg.norm(m.points - center, axis=1) - radius
            ins = d < 0
        closest, inside = min(closest, d.min()), inside + int(ins.any())
    return closest, inside, frames


def last_time_error(run):
    te = io.read_summary(run, required=True).get("time_error")
    if not isinstance(te, dict) or "max_per_frame_m" not in te:
        raise io.RunError(f"{run}: summary.json has no time_error (run it with --error-estimate)")
    return te["max_per_frame_m"][-1]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("scene")
    ap.add_argument("--runs", nargs="+", required=True, metavar="MODEL:SPHERE_RUN:MESH_RUN")
    ap.add_argument("--obstacles", required=True)
    ap.add_argument("--positions", required=True)
    a = ap.parse_args()
    center, radius = sphere_of(a.scene)
    obstacles, positions = [], []
    for item in a.runs:
        parts = item.split(":")
        if len(parts) != 3:
            raise io.RunError(f"--runs '{item}': expected MODEL:SPHERE_RUN:MESH_RUN")
        model, sphere_run, mesh_run = parts
        final, median = {}, {}
        for name, run in (("sphere", sphere_run), ("mesh", mesh_run)):
            closest, inside, frames = closest_over_frames(run, center, radius, name == "mesh")
            final[name] = frames[-1][1].points
            times = io.step_wall_times(io.read_metrics(run), run)
            median[name] = statistics.median(times)
            rejected = io.read_summary(run, required=True).get("statistics", {}).get("rejected_steps", 0)
            obstacles.append([model, name, f"{closest:.6g}", inside, len(frames), f"{1e3 * median[name]:.6g}",
                              len(times), rejected])
        gap = np.linalg.norm(final["mesh"] - final["sphere"], axis=1)
        positions.append([model, f"{median['mesh'] / median['sphere']:.4g}", f"{gap.max():.6g}",
                          f"{np.sqrt((gap ** 2).mean()):.6g}", f"{last_time_error(sphere_run):.6g}",
                          f"{last_time_error(mesh_run):.6g}"])
    write_csv(a.obstacles, ["model", "obstacle", "closest_node_m", "frames_with_a_node_inside", "frames",
                            "median_step_ms", "steps", "rejected"], obstacles)
    write_csv(a.positions, ["model", "step_time_mesh_over_sphere", "final_gap_largest_m", "final_gap_rms_m",
                            "time_error_last_frame_sphere_m", "time_error_last_frame_mesh_m"], positions)


if __name__ == "__main__":
    try:
        main()
    except io.RunError as e:
        io.fail(str(e))
