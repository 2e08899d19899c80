#!/usr/bin/env python3
"""Drape coefficient and fold count of a cloth over a disk pedestal, per frame
(docs/models.md §3.11; the scenes experiments/scenes/cusick_drape_*.toml, the
study experiments/cusick/).

    drape_measure.py RUN SCENE [--out CSV] [--state]

The cloth's cells (yarn quads or FEM triangles) are projected onto the plane
of the pedestal's top (xy) and rasterized at 0.1 mm (a pixel counts when its
centre lies in a projected cell); the drape coefficient is
(A_projected − A_pedestal) / (A_cloth − A_pedestal), A_cloth the flat cloth's
area, so a flat cloth gives 1 and one hanging straight down gives 0. Folds:
the shadow's outer radius r(φ) about the pedestal's axis in 1° bins, smoothed
over 5°, and its local maxima that stand 0.5 mm above both neighbouring
minima (a flat square shows its 4 corners). --state adds, per frame, the
kinetic energy (metrics.csv at the frame's time), the intersecting triangle
pairs of the cloth (self_intersections.csv) and the closest signed distance of
a node to the pedestal (negative: inside)."""
import argparse, csv, math, os, sys, tomllib
import numpy as np
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "common"))
import runs as io  # noqa: E402


def shadow(points, cells, lo, hi, step):
    nx, ny = (np.ceil((hi - lo) / step)).astype(int)
    gx, gy = lo[0] + step * (0.5 + np.arange(nx)), lo[1] + step * (0.5 + np.arange(ny))
    mask = np.zeros((nx, ny), dtype=bool)
    for cell in cells:
        for tri in ([cell[0], cell[1], cell[2]],) if len(cell) == 3 else ([cell[0], cell[1], cell[2]], [cell[0], cell[2], cell[3]]):
            a, b, c = points[tri, :2]
            x0, x1 = min(a[0], b[0], c[0]), max(a[0], b[0], c[0])
            y0, y1 = min(a[1], b[1], c[1]), max(a[1], b[1], c[1])
            i0, i1 = np.searchsorted(gx, x0), np.searchsorted(gx, x1, side="right")
            j0, j1 = np.searchsorted(gy, y0), np.searchsorted(gy, y1, side="right")
            if i0 >= i1 or j0 >= j1:
                continue
            X, Y = np.meshgrid(gx[i0:i1], gy[j0:j1], indexing="ij")
            det = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
            if det == 0:
                continue
            l1 = ((X - a[0]) * (c[1] - a[1]) - (Y - a[1]) * (c[0] - a[0])) / det
            l2 = ((b[0] - a[0]) * (Y - a[1]) - (b[1] - a[1]) * (X - a[0])) / det
            mask[i0:i1, j0:j1] |= (l1 >= 0) & (l2 >= 0) & (l1 + l2 <= 1)
    X, Y = np.meshgrid(gx, gy, indexing="ij")
    return mask, X, Y


def folds(mask, X, Y, centre):
    phi = np.degrees(np.arctan2(Y[mask] - centre[1], X[mask] - centre[0])) % 360
    r = np.hypot(X[mask] - centre[0], Y[mask] - centre[1])
    radius = np.zeros(360)
    np.maximum.at(radius, phi.astype(int) % 360, r)
    smooth = np.convolve(np.concatenate([radius[-2:], radius, radius[:2]]), np.ones(5) / 5, mode="valid")
    count = 0
    for k in range(360):
        if smooth[k] <= smooth[k - 1] or smooth[k] < smooth[(k + 1) % 360]:
            continue
        left = min(smooth[(k - d) % 360] for d in range(0, 90) if all(smooth[(k - e) % 360] <= smooth[k] for e in range(d + 1)))
        right = min(smooth[(k + d) % 360] for d in range(0, 90) if all(smooth[(k + e) % 360] <= smooth[k] for e in range(d + 1)))
        if smooth[k] - max(left, right) >= 0.5e-3:
            count += 1
    return count


def pedestal_distance(points, disk):
    """Signed distance of each point to an unrotated disk or cylinder (docs/models.md §3.11.1)."""
    if any(disk.get("rotation_deg", [0, 0, 0])):
        raise SystemExit("drape_measure.py: --state needs an unrotated pedestal")
    c = np.array(disk["center_m"])
    a = 0.5 * disk.get("thickness_m", disk.get("height_m", 0.0))
    rho = np.linalg.norm(points[:, :2] - c[:2], axis=1)
    w = np.stack([rho - disk["radius_m"], np.abs(points[:, 2] - c[2]) - a], axis=1)
    return np.linalg.norm(np.maximum(w, 0.0), axis=1) + np.minimum(w.max(axis=1), 0.0)


def frame_state(run, times):
    """Kinetic energy and self-intersecting pairs at the frame times."""
    m = io.read_metrics(run)
    ke = [float(m["kinetic_J"][np.argmin(np.abs(m["time_s"] - t))]) for t in times]
    with open(f"{io.run_dir(run)}/self_intersections.csv", newline="") as f:
        rows = [[float(x) for x in r] for r in list(csv.reader(f))[1:]]
    pairs = {round(r[0], 9): int(r[1]) for r in rows}
    return ke, [pairs.get(round(t, 9), -1) for t in times]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("run")
    ap.add_argument("scene")
    ap.add_argument("--out")
    ap.add_argument("--state", action="store_true", help="add kinetic energy, self-intersections, pedestal distance")
    a = ap.parse_args()
    with open(a.scene, "rb") as f:
        scene = tomllib.load(f)
    disk = next(o for o in scene["obstacles"] if o["shape"] in ("disk", "cylinder", "sphere"))
    centre, r = np.array(disk["center_m"][:2]), disk["radius_m"]
    L = scene["cloth"]["spacing_m"]
    side_u, side_v = (scene["cloth"]["wefts"] - 1) * L, (scene["cloth"]["warps"] - 1) * L
    a_cloth, a_ped = side_u * side_v, math.pi * r * r
    rows, closest = [], []
    for t, mesh in io.read_frames(a.run):
        if a.state:
            closest.append(float(pedestal_distance(mesh.points, disk).min()))
        cells = [c for block in mesh.cells if block.type in ("triangle", "quad") for c in block.data]
        lo, hi = mesh.points[:, :2].min(axis=0), mesh.points[:, :2].max(axis=0)
        step = 1e-4
        mask, X, Y = shadow(mesh.points, cells, lo, hi, step)
        area = mask.sum() * step * step
        rows.append((t, (area - a_ped) / (a_cloth - a_ped), folds(mask, X, Y, centre)))
        print(f"t = {t:.3f} s  drape coefficient {rows[-1][1]:.3f}  folds {rows[-1][2]}")
    header = ["time_s", "drape_coefficient", "folds"]
    if a.state:
        ke, pairs = frame_state(a.run, [r[0] for r in rows])
        rows = [r + (k, p, c) for r, k, p, c in zip(rows, ke, pairs, closest)]
        header += ["kinetic_J", "intersecting_triangle_pairs", "closest_to_pedestal_m"]
        r = rows[-1]
        print(f"t = {r[0]:.3f} s  kinetic energy {r[3]:.3g} J  intersecting pairs {r[4]}  closest node {r[5]:.3g} m")
    if a.out:
        with open(a.out, "w", newline="") as f:
            w = csv.writer(f, lineterminator="\n")
            w.writerow(header)
            w.writerows(rows)


if __name__ == "__main__":
    main()
