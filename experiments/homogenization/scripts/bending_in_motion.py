"""The continua's bending and membrane energy in motion against the yarn level's,
from `weavelab diagnose` folders.

usage: bending_in_motion.py FROM_S TO_S TABLE_CSV LABEL=DIAGNOSE_DIR ...

Each DIAGNOSE_DIR holds energies.csv (time_s, model, quantity, value_J): per
output frame the potential of every term of the yarn level (model yarn) and of
the continuum (model fem). TABLE_CSV: per LABEL and energy (bending: the yarn
level's bending against the continuum's fem-bending, fem-grid-line-bending or
fem-tile-bending; membrane: the yarn level's stretch and shear against the
continuum's fem-stretch, fem-shear, fem-border-stretch or fem-tile-membrane),
each side's change since t = 0 averaged over the frames in [FROM_S, TO_S], and
the continuum's over the yarn level's.
Missing or malformed input: a message, exit 2, nothing written.
"""
import csv
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "common"))
from runs import fail  # noqa: E402

KINDS = {"bending": ({"bending"}, {"fem-bending", "fem-grid-line-bending", "fem-tile-bending"}),
         "membrane": ({"stretch", "shear"}, {"fem-stretch", "fem-shear", "fem-border-stretch", "fem-tile-membrane"})}


def mean_change(series, t_from, t_to, where):
    """Mean over the frames in [t_from, t_to] of the energy's change since the first frame."""
    if not series:
        fail(f"{where}: no rows")
    start = series[min(series)]
    window = [e - start for t, e in series.items() if t_from - 1e-12 <= t <= t_to + 1e-12]
    if not window:
        fail(f"{where}: no frame in [{t_from}, {t_to}] s")
    return sum(window) / len(window)


def rows_of(label, folder, t_from, t_to):
    path = os.path.join(folder, "energies.csv")
    series = {}  # (model, kind) -> time -> J
    try:
        with open(path, newline="", encoding="utf-8") as f:
            for r in csv.DictReader(f):
                side = 0 if r["model"] == "yarn" else 1
                for kind, names in KINDS.items():
                    if r["quantity"] in names[side]:
                        by_time = series.setdefault((r["model"], kind), {})
                        t = float(r["time_s"])
                        by_time[t] = by_time.get(t, 0.0) + float(r["value_J"])
    except (OSError, KeyError, ValueError) as e:
        fail(f"{path}: not a diagnose energy table ({e})")
    rows = []
    for kind in KINDS:
        yarn = mean_change(series.get(("yarn", kind)), t_from, t_to, f"{path}: yarn {kind}")
        fem = mean_change(series.get(("fem", kind)), t_from, t_to, f"{path}: fem {kind}")
        rows.append({"continuum": label, "energy": kind, "yarn_J": yarn, "continuum_J": fem,
                     "continuum_over_yarn": fem / yarn if yarn != 0 else float("nan")})
    return rows


def main(argv):
    if len(argv) < 5 or any("=" not in a for a in argv[4:]):
        fail(__doc__)
    try:
        t_from, t_to = float(argv[1]), float(argv[2])
    except ValueError:
        fail(f"FROM_S and TO_S: got {argv[1]!r} {argv[2]!r}, expected numbers [s]")
    rows = []
    for label, folder in (a.split("=", 1) for a in argv[4:]):
        rows += rows_of(label, folder, t_from, t_to)
    with open(argv[3] + ".tmp", "w", newline="", encoding="utf-8") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        for r in rows:
            w.writerow({k: (f"{v:.4g}" if isinstance(v, float) else v) for k, v in r.items()})
    os.replace(argv[3] + ".tmp", argv[3])


if __name__ == "__main__":
    main(sys.argv)
