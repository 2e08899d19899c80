#!/usr/bin/python3
"""Distance between two runs of the same scene, frame by frame.

    compare.py RUN_A RUN_B --out CSV [--plot PNG]

Frames are paired by time (equal within 1e-9 of the output interval). For each
pair, every point of run A (yarn crossings with point data "u", "v", or a
continuum mesh with "uv": material coordinates in metres) is compared with run
B's surface at the same material point: B carries rest material coordinates
"uv" and triangles; the triangle holding (u, v) in the UV plane is found
(points outside B's UV domain use the nearest triangle, barycentrics clamped)
and B's positions are interpolated barycentrically. Two runs of the same yarn
model (B without "uv", the same number of points) are paired point by point.

CSV columns: time_s, rms_distance_m, max_distance_m, step_time_ratio_B_over_A
(median "step_wall_s" of B over that of A, without the initial-state row;
one value for the whole run).
--plot writes the RMS and max distance over time as PNG and SVG; --table
prints the per-frame distances (mm) on stdout. The closing lines set the mean
distance beside each run's estimated time error (summary.json "time_error",
written by `weavelab run --error-estimate`) and say whether the distance
measures the models or is within the runs' own time error.
Missing or malformed inputs: a message on stderr and exit status 2.
"""
import argparse
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import runs as wio  # noqa: E402

RELATIVE_TIME_TOLERANCE = 1e-9  # of the output interval


# --------------------------------------------------------------------------
# Locating material points in a UV triangle mesh
# --------------------------------------------------------------------------

def barycentric(p, a, b, c):
    """Barycentric coordinates of points p (k, 2) in triangles (a, b, c) (k, 2 each)."""
    v0, v1, v2 = b - a, c - a, p - a
    d00 = np.einsum("ij,ij->i", v0, v0)
    d01 = np.einsum("ij,ij->i", v0, v1)
    d11 = np.einsum("ij,ij->i", v1, v1)
    d20 = np.einsum("ij,ij->i", v2, v0)
    d21 = np.einsum("ij,ij->i", v2, v1)
    den = d00 * d11 - d01 * d01
    den = np.where(den == 0.0, np.finfo(float).tiny, den)  # degenerate triangles never win
    l1 = (d11 * d20 - d01 * d21) / den
    l2 = (d00 * d21 - d01 * d20) / den
    return np.column_stack([1.0 - l1 - l2, l1, l2])


class UvLocator:
    """Finds, for query points in the UV plane, a triangle and barycentric
    weights. A uniform bucket grid over the triangles' UV bounding boxes gives
    candidates; queries inside no triangle fall back to the nearest triangle
    (searched over all triangles) with clamped barycentrics."""

    def __init__(self, uv, triangles):
        self.uv = np.asarray(uv, dtype=float)
        self.tri = np.asarray(triangles, dtype=np.int64)
        if self.tri.size == 0:
            raise wio.RunError("run B has no triangles to interpolate on")
        corners = self.uv[self.tri]  # (T, 3, 2)
        self.lo = corners.min(axis=1)
        self.hi = corners.max(axis=1)
        span = np.maximum(self.hi.max(axis=0) - self.lo.min(axis=0), 1e-300)
        self.origin = self.lo.min(axis=0)
        n = max(1, int(np.sqrt(len(self.tri))))
        self.n = n
        self.cell = span / n
        i0 = self._cell_index(self.lo)
        i1 = self._cell_index(self.hi)
        # (bucket, triangle) pairs for every bucket a triangle's box touches.
        nx = i1[:, 0] - i0[:, 0] + 1
        ny = i1[:, 1] - i0[:, 1] + 1
        counts = nx * ny
        tri_ids = np.repeat(np.arange(len(self.tri)), counts)
        local = np.arange(counts.sum()) - np.repeat(np.cumsum(counts) - counts, counts)
        bx = i0[tri_ids, 0] + local % nx[tri_ids]
        by = i0[tri_ids, 1] + local // nx[tri_ids]
        bucket = bx * n + by
        order = np.argsort(bucket, kind="stable")
        self.bucket_tris = tri_ids[order]
        self.bucket_start = np.searchsorted(bucket[order], np.arange(n * n + 1))

    def _cell_index(self, p):
        return np.clip(((p - self.origin) / self.cell).astype(np.int64), 0, self.n - 1)

    def locate(self, q, eps=1e-12):
        """(triangle index (k,), barycentrics (k, 3)) for query points q (k, 2)."""
        q = np.asarray(q, dtype=float)
        k = len(q)
        best_tri = np.full(k, -1, dtype=np.int64)
        best_w = np.zeros((k, 3))
        c = self._cell_index(q)
        b = c[:, 0] * self.n + c[:, 1]
        start, stop = self.bucket_start[b], self.bucket_start[b + 1]
        counts = stop - start
        if counts.sum() > 0:
            query_ids = np.repeat(np.arange(k), counts)
            offsets = np.arange(counts.sum()) - np.repeat(np.cumsum(counts) - counts, counts)
            tris = self.bucket_tris[np.repeat(start, counts) + offsets]
            corners = self.uv[self.tri[tris]]
            w = barycentric(q[query_ids], corners[:, 0], corners[:, 1], corners[:, 2])
            score = w.min(axis=1)
            # Per query, the candidate with the largest smallest weight.
            order = np.lexsort((-score, query_ids))
            first = np.ones(len(order), dtype=bool)
            first[1:] = query_ids[order][1:] != query_ids[order][:-1]
            pick = order[first]
            inside = score[pick] >= -eps
            hit = query_ids[pick][inside]
            best_tri[hit] = tris[pick][inside]
            best_w[hit] = w[pick][inside]
        outside = np.nonzero(best_tri < 0)[0]
        if len(outside):
            t, w = self._nearest(q[outside])
            best_tri[outside] = t
            best_w[outside] = w
        return best_tri, best_w

    def _nearest(self, q, block=256):
        """Nearest triangle (by closest boundary point) and clamped barycentrics."""
        a, b, c = (self.uv[self.tri[:, j]] for j in range(3))
        edges = [(a, b, (0, 1)), (b, c, (1, 2)), (c, a, (2, 0))]
        tris = np.empty(len(q), dtype=np.int64)
        weights = np.zeros((len(q), 3))
        for s in range(0, len(q), block):
            p = q[s:s + block, None, :]  # (m, 1, 2)
            best_d = best_t = best_e = None
            for edge_index, (p0, p1, _) in enumerate(edges):
                e = (p1 - p0)[None]  # (1, T, 2)
                ee = np.maximum((e * e).sum(-1), 1e-300)
                t = np.clip(((p - p0[None]) * e).sum(-1) / ee, 0.0, 1.0)  # (m, T)
                d = ((p0[None] + t[..., None] * e - p) ** 2).sum(-1)
                if best_d is None:
                    best_d, best_t, best_e = d, t, np.zeros(d.shape, dtype=np.int8)
                else:
                    better = d < best_d
                    best_d = np.where(better, d, best_d)
                    best_t = np.where(better, t, best_t)
                    best_e = np.where(better, edge_index, best_e)
            m = np.arange(best_d.shape[0])
            tri = best_d.argmin(axis=1)
            t = best_t[m, tri]
            e = best_e[m, tri]
            w = np.zeros((len(m), 3))
            for edge_index, (_, _, (i, j)) in enumerate(edges):
                sel = e == edge_index
                w[sel, i] = 1.0 - t[sel]
                w[sel, j] = t[sel]
            tris[s:s + block] = tri
            weights[s:s + block] = w
        return tris, weights


def interpolate(values, triangles, tri, w):
    """Barycentric interpolation of per-point `values` at located points."""
    return np.einsum("kj,kjd->kd", w, values[triangles[tri]])


# --------------------------------------------------------------------------
# Comparing two runs
# --------------------------------------------------------------------------

def pair_frames(times_a, times_b):
    """[(index in A, index in B)] of frames whose times agree within
    RELATIVE_TIME_TOLERANCE of the output interval."""
    ta, tb = np.asarray(times_a, float), np.asarray(times_b, float)
    steps = np.diff(np.unique(np.concatenate([ta, tb])))
    steps = steps[steps > 0]
    interval = float(np.median(np.diff(ta))) if len(ta) > 1 else (float(steps.min()) if len(steps) else 1.0)
    tol = RELATIVE_TIME_TOLERANCE * abs(interval) if interval else 1e-9
    pairs = []
    if len(tb) == 0:
        return pairs
    for i, t in enumerate(ta):
        j = int(np.argmin(np.abs(tb - t)))
        if abs(tb[j] - t) <= tol:
            pairs.append((i, j))
    return pairs


_cached_locator = None


def _locator_for(uv, triangles):
    """A UvLocator, reused while B's rest coordinates and triangles stay the same."""
    global _cached_locator
    c = _cached_locator
    if c is None or not (np.array_equal(c.uv, uv) and np.array_equal(c.tri, triangles)):
        _cached_locator = c = UvLocator(uv, triangles)
    return c


def frame_distance(mesh_a, mesh_b, label_a="A", label_b="B"):
    """Distances (per point of A) between A's points and B's surface at A's material coordinates."""
    x_a = np.asarray(mesh_a.points, float)[:, :3]
    if "uv" not in mesh_b.point_data and len(mesh_b.points) == len(x_a):
        # Two runs of the same model (no surface to interpolate): points paired by index.
        return np.linalg.norm(x_a - np.asarray(mesh_b.points, float)[:, :3], axis=1)
    uv_a = wio.material_coordinates(mesh_a, label_a)
    if "uv" not in mesh_b.point_data:
        raise wio.RunError(f"{label_b}: run B needs point data 'uv' (rest material coordinates) and triangles")
    uv_b = wio.material_coordinates(mesh_b, label_b)
    tri_b = wio.cells_with_data(mesh_b, "triangle", path=label_b)
    locator = _locator_for(uv_b, tri_b)
    tri, w = locator.locate(uv_a)
    x_b = interpolate(np.asarray(mesh_b.points, float)[:, :3], tri_b, tri, w)
    return np.linalg.norm(x_a - x_b, axis=1)


def median_step_time(metrics, label):
    column = wio.step_wall_times(metrics, label)
    if len(column) == 0:
        raise wio.RunError(f"{label}: metrics.csv has no step rows")
    return float(np.median(column))


def compare(run_a, run_b):
    """Rows (time, rms, max, ratio) and the two run labels."""
    frames_a, frames_b = wio.read_frames(run_a), wio.read_frames(run_b)
    metrics_a, metrics_b = wio.read_metrics(run_a), wio.read_metrics(run_b)
    label_a, label_b = wio.run_label(run_a), wio.run_label(run_b)
    step_a = median_step_time(metrics_a, run_a)
    step_b = median_step_time(metrics_b, run_b)
    ratio = step_b / step_a if step_a > 0 else float("nan")
    pairs = pair_frames([t for t, _ in frames_a], [t for t, _ in frames_b])
    if not pairs:
        raise wio.RunError(f"no frame times in common between '{run_a}' ({len(frames_a)} frames) "
                           f"and '{run_b}' ({len(frames_b)} frames)")
    rows = []
    for i, j in pairs:
        t, mesh_a = frames_a[i]
        d = frame_distance(mesh_a, frames_b[j][1], f"{run_a} frame {i}", f"{run_b} frame {j}")
        rows.append((t, float(np.sqrt(np.mean(d ** 2))) if len(d) else 0.0, float(d.max()) if len(d) else 0.0, ratio))
    return rows, label_a, label_b


def write_csv(path, rows):
    lines = ["time_s,rms_distance_m,max_distance_m,step_time_ratio_B_over_A"]
    lines += [",".join(repr(float(x)) for x in row) for row in rows]
    wio.write_text_atomically(path, "\n".join(lines) + "\n")


def material_size(run):
    """Largest extent [m] of the material coordinates of run's first frame (for
    a relative distance axis); None when it cannot be read."""
    try:
        frames = wio.read_pvd(wio.find_pvd(run))
        uv = wio.material_coordinates(wio.read_mesh(frames[0][1]), run) if frames else None
    except wio.RunError:
        return None
    if uv is None or len(uv) == 0:
        return None
    size = float((uv.max(axis=0) - uv.min(axis=0)).max())
    return size if size > 0 else None


def plot(path, rows, label_a, label_b, size_m=None):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    t = np.array([r[0] for r in rows])
    fig, ax = plt.subplots(figsize=(8, 4.5))
    ax.plot(t, 1e3 * np.array([r[1] for r in rows]), "o-", ms=4, label="RMS over A's points")
    ax.plot(t, 1e3 * np.array([r[2] for r in rows]), "s--", ms=4, label="max over A's points")
    ax.set_xlabel("time (s)")
    ax.set_ylabel("distance (mm)")
    ax.set_title(f"Distance between A's points and B's surface at the same material (u, v)\n"
                 f"A: {label_a}    B: {label_b}\n"
                 f"median step wall time B/A = {rows[0][3]:.3g}", fontsize="medium")
    ax.set_ylim(bottom=0.0)
    ax.ticklabel_format(axis="y", useOffset=False)
    ax.grid(True, alpha=0.3)
    ax.legend(loc="upper left")
    if size_m:
        scale = 1e-3 / size_m * 100.0  # mm -> % of the cloth size
        right = ax.secondary_yaxis("right", functions=(lambda d: d * scale, lambda p: p / scale))
        right.set_ylabel(f"% of cloth size ({1e3 * size_m:.3g} mm)")
    written = wio.save_figure(fig, path, svg=True)
    plt.close(fig)
    return written


def time_error(run):
    """The run's estimated time error (summary.json "time_error", docs/models.md §7.8) as
    (mean RMS, max, method), or None when the run carries no estimate."""
    te = (wio.read_summary(run) or {}).get("time_error") or {}
    if "mean_rms_m" not in te:
        return None
    return float(te["mean_rms_m"]), float(te["max_m"]), te.get("method", "?")


def error_budget(rows, run_a, run_b):
    """Lines that set the mean RMS distance beside each run's own time error."""
    distance = float(np.mean([r[1] for r in rows[1:]] if len(rows) > 1 else [r[1] for r in rows]))
    lines = [f"distance: {1e3 * distance:.4g} mm (mean over frames after t = 0 of the RMS)"]
    errors = []
    for label, run in (("A", run_a), ("B", run_b)):
        te = time_error(run)
        if te is None:
            lines.append(f"time error of {label} ({run}): not estimated (rerun it with --error-estimate)")
            errors.append(None)
        else:
            lines.append(f"time error of {label} ({run}): {1e3 * te[0]:.4g} mm mean RMS, {1e3 * te[1]:.4g} mm max "
                         f"({te[2]})")
            errors.append(te[0])
    known = [e for e in errors if e is not None]
    if len(known) < 2:
        lines.append("budget: incomplete: the distance may be time error")
    elif max(known) > distance:
        lines.append("budget: a time error EXCEEDS the distance: the distance does not measure the models")
    elif max(known) > 0.1 * distance:
        lines.append("budget: a time error is above a tenth of the distance: the models are not resolved apart")
    else:
        lines.append("budget: both time errors are below a tenth of the distance")
    return lines


def format_table(rows):
    """The per-frame distances as a text table (mm)."""
    lines = [f"{'time (s)':>9} {'RMS (mm)':>9} {'max (mm)':>9}"]
    lines += [f"{r[0]:9.4g} {1e3 * r[1]:9.4f} {1e3 * r[2]:9.4f}" for r in rows]
    return "\n".join(lines)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("run_a", metavar="RUN_A", help="reference run folder (yarn or continuum)")
    parser.add_argument("run_b", metavar="RUN_B", help="continuum run folder (point data 'uv', triangles)")
    parser.add_argument("--out", required=True, metavar="CSV", help="distance table to write")
    parser.add_argument("--plot", metavar="PNG", help="also plot distances (PNG and SVG beside it)")
    parser.add_argument("--table", action="store_true", help="print the per-frame distances (mm) on stdout")
    args = parser.parse_args(argv)
    try:
        rows, label_a, label_b = compare(args.run_a, args.run_b)
        write_csv(args.out, rows)
        written = plot(args.plot, rows, label_a, label_b, material_size(args.run_b)) if args.plot else []
    except wio.RunError as e:
        wio.fail(str(e))
    if args.table:
        print(format_table(rows))
    worst = max(rows, key=lambda r: r[2])
    print(f"{len(rows)} frame pairs; max distance {1e3 * worst[2]:.4g} mm at t = {worst[0]:.6g} s; "
          f"step time ratio B/A = {rows[0][3]:.4g}; wrote {', '.join([args.out] + written)}")
    print("\n".join(error_budget(rows, args.run_a, args.run_b)))
    return 0


if __name__ == "__main__":
    sys.exit(main())
