"""Where the tile law misses the moments, and what richer bending bases buy.

usage: moment_basis.py CELL REGIONS_CSV BASES_CSV

CELL is a `weavelab tiles` folder (tiles.json, held_out.csv, the samples file).

REGIONS_CSV: the law's held-out moment errors (held_out.csv, the law of
`weavelab tiles`) split by where the sample lies: near the shear lock
(|γ| ≥ 0.9 of the range's bound), in biaxial compression (ε_u < 0 and
ε_v < 0, outside the lock band), and elsewhere. Per region and moment the
share of the held-out samples' squared error and the relative RMS error there.

BASES_CSV: the law refitted on the same fitted samples, with the same
residuals and weights (docs/calibration.md §9.3) by linear least squares, with
the polynomial basis alone and with added bending terms:
  spline   κ_a² N_j(θ_b): cubic B-splines N_j (8 per strain, uniform over the
           range) of each membrane strain θ_b, for the three curvatures a;
  lock     κ_a² t_γ^p, p = 8, 12, 16, 24 (the bending near the shear lock);
  compression  κ_a² min(t_b, 0)^p, p = 1, 2, 3, of both stretches;
and the relative RMS errors on the held-out samples. The polynomial row is
checked against tiles.json: the refit must reproduce the law's held-out errors
(to 1e-6), or the script fails.
Missing or malformed input: a message, exit 2, nothing written.
"""
import csv
import itertools
import json
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "common"))
from runs import fail  # noqa: E402

NAMES = ["stretch_warp", "stretch_weft", "shear", "curvature_warp", "curvature_weft", "twist"]
MOMENTS = [3, 4, 5]


def load(cell):
    try:
        with open(os.path.join(cell, "tiles.json")) as f:
            summary = json.load(f)
        rows = np.genfromtxt(os.path.join(cell, summary["samples_file"]), delimiter=",", skip_header=2)
        with open(os.path.join(cell, "held_out.csv"), newline="") as f:
            held = list(csv.DictReader(f))
    except (OSError, ValueError, KeyError) as e:
        fail(f"{cell}: {e}")
    lo = np.array([summary["ranges"][n][0] for n in NAMES])
    hi = np.array([summary["ranges"][n][1] for n in NAMES])
    return summary, rows, held, lo, hi


def regions(held, lo, hi):
    """Rows: region, count, then per moment the share of squared error and the relative RMS error."""
    lock = 0.9 * max(abs(lo[2]), abs(hi[2]))
    x = {n: np.array([float(r[n]) for r in held]) for n in NAMES}
    near_lock = np.abs(x["shear"]) >= lock
    compressed = (x["stretch_warp"] < 0) & (x["stretch_weft"] < 0) & ~near_lock
    masks = {"all": np.ones(len(held), bool), "near_shear_lock": near_lock, "biaxial_compression": compressed,
             "elsewhere": ~near_lock & ~compressed}
    out = []
    for region, m in masks.items():
        row = {"region": region, "count": int(m.sum())}
        for k in MOMENTS:
            s = np.array([float(r[f"dW_d{NAMES[k]}"]) for r in held])
            law = np.array([float(r[f"law_dW_d{NAMES[k]}"]) for r in held])
            e2 = (law - s) ** 2
            row[f"{NAMES[k]}_share"] = e2[m].sum() / e2.sum()
            row[f"{NAMES[k]}_error"] = np.sqrt(e2[m].sum() / (s[m] ** 2).sum()) if m.any() else float("nan")
        out.append(row)
    return out


def polynomial_exponents():
    """The basis of calibration/tile_law.h: degree 2 … 8, pairs to 6, three or more strains to 4."""
    out = []
    for e in itertools.product(range(9), repeat=6):
        degree, used = sum(e), sum(1 for x in e if x)
        if 2 <= degree <= 8 and (used == 1 or (used == 2 and degree <= 6) or (used >= 3 and degree <= 4)):
            out.append(e)
    return out


def polynomial(t):
    """Values (n × m) and derivatives (n × 6 × m) of the basis at normalized strains t."""
    exps = polynomial_exponents()
    powers = [[t[:, k] ** p for p in range(9)] for k in range(6)]
    value = np.zeros((len(t), len(exps)))
    deriv = np.zeros((len(t), 6, len(exps)))
    for i, e in enumerate(exps):
        value[:, i] = np.prod([powers[k][e[k]] for k in range(6)], axis=0)
        for k in range(6):
            if e[k]:
                deriv[:, k, i] = e[k] * powers[k][e[k] - 1] * np.prod(
                    [powers[j][e[j]] for j in range(6) if j != k], axis=0)
    return value, deriv


def bspline(x, lo, hi, n):
    """n uniform cubic B-splines over [lo, hi] and their derivatives."""
    h = (hi - lo) / (n - 3)
    value, deriv = np.zeros((len(x), n)), np.zeros((len(x), n))
    for j in range(n):
        u = (x - (lo + (j - 1) * h)) / h
        a = np.abs(u)
        value[:, j] = np.where(a < 1, 2 / 3 - a ** 2 + a ** 3 / 2, np.where(a < 2, (2 - a) ** 3 / 6, 0))
        deriv[:, j] = np.where(a < 1, -2 * a + 1.5 * a ** 2, np.where(a < 2, -0.5 * (2 - a) ** 2, 0)) * np.sign(u) / h
    return value, deriv


def product(t, a, factor, dfactor, b):
    """t_a² f(t_b) and its derivatives."""
    d = np.zeros((len(t), 6))
    d[:, a] = 2 * t[:, a] * factor
    d[:, b] += t[:, a] ** 2 * dfactor
    return t[:, a] ** 2 * factor, d


def extra(kind, t, tlo, thi):
    cols = []
    for a in MOMENTS:
        if kind == "spline":
            for b in (0, 1, 2):
                v, d = bspline(t[:, b], tlo[b], thi[b], 8)
                cols += [product(t, a, v[:, j], d[:, j], b) for j in range(8)]
        elif kind == "lock":
            cols += [product(t, a, t[:, 2] ** p, p * t[:, 2] ** (p - 1), 2) for p in (8, 12, 16, 24)]
        else:
            for b in (0, 1):
                n = np.minimum(t[:, b], 0)
                cols += [product(t, a, n ** p, p * n ** (p - 1), b) for p in (1, 2, 3)]
    return np.array([c[0] for c in cols]).T, np.transpose(np.array([c[1] for c in cols]), (1, 2, 0))


def errors(value, deriv, w, s, scale, fitted, held):
    """Fit on `fitted` (energies and stresses, scaled by their RMS), relative RMS errors on `held`."""
    w0 = np.sqrt(np.mean(w[fitted] ** 2))
    s0 = np.sqrt(np.mean(s[fitted] ** 2, axis=0))
    a = np.vstack([value[fitted]] + [deriv[fitted, k, :] * w0 / (scale[k] * s0[k]) for k in range(6)])
    b = np.concatenate([w[fitted] / w0] + [s[fitted, k] / s0[k] for k in range(6)])
    c = np.linalg.lstsq(a, b, rcond=None)[0]
    out = [np.sqrt(np.sum((w0 * value[held] @ c - w[held]) ** 2) / np.sum(w[held] ** 2))]
    for k in range(6):
        law = w0 / scale[k] * deriv[held, k, :] @ c
        out.append(np.sqrt(np.sum((law - s[held, k]) ** 2) / np.sum(s[held, k] ** 2)))
    return out


def bases(summary, rows, lo, hi):
    strain, w, s = rows[:, :6], rows[:, 6], rows[:, 7:13]
    converged = rows[:, 13] == 1
    every = summary["law"]["holdout_every"]
    held = converged & (np.arange(len(rows)) % every == every - 1)
    fitted = converged & ~held
    scale = np.maximum(np.abs(lo), np.abs(hi))
    t = strain / scale
    value, deriv = polynomial(t)
    variants = [("polynomial", [])], [("polynomial + spline", ["spline"]), ("polynomial + lock", ["lock"]),
                                      ("polynomial + lock + compression", ["lock", "compression"])]
    out = []
    for name, kinds in variants[0] + variants[1]:
        v, d = value, deriv
        for kind in kinds:
            ev, ed = extra(kind, t, lo / scale, hi / scale)
            v, d = np.hstack([v, ev]), np.concatenate([d, ed], axis=2)
        e = errors(v, d, w, s, scale, fitted, held)
        out.append({"basis": name, "size": v.shape[1], "energy": e[0],
                    **{f"stress_{NAMES[k]}": e[1 + k] for k in range(6)}})
    reference = summary["law"]["held_out"]
    mine = [out[0]["energy"]] + [out[0][f"stress_{n}"] for n in NAMES]
    theirs = [reference["energy_relative_rms"]] + [reference["stress_relative_rms"][n] for n in NAMES]
    if max(abs(a - b) for a, b in zip(mine, theirs)) > 1e-6:
        fail(f"the polynomial refit's held-out errors {mine} differ from tiles.json's {theirs}")
    return out


def write(path, rows):
    tmp = path + ".tmp"
    with open(tmp, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows({k: (f"{v:.6g}" if isinstance(v, float) else v) for k, v in r.items()} for r in rows)
    return tmp


def main(argv):
    if len(argv) != 4:
        fail(__doc__)
    cell, regions_csv, bases_csv = argv[1:4]
    summary, rows, held, lo, hi = load(cell)
    done = [(write(regions_csv, regions(held, lo, hi)), regions_csv), (write(bases_csv, bases(summary, rows, lo, hi)),
                                                                         bases_csv)]
    for tmp, path in done:
        os.replace(tmp, path)


if __name__ == "__main__":
    main(sys.argv)
