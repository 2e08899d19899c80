"""The continua against the yarn level, from `weavelab fidelity` rung folders.

usage: compare_tables.py SCENE TABLE_CSV FIGURE_PNG LABEL=RUNG_DIR ...

Each RUNG_DIR is a `weavelab fidelity --variants fem_s1,... --reference-from ...`
folder: its fidelity.csv holds the reference's row (full, the yarn level) and
the continuum's (fem_s1, fem_s2, ...: a vertex at every crossing, every second,
...). TABLE_CSV: per LABEL and stride the continuum's RMS distance
from the yarn crossings over all frames, as a share of the cloth's side
((warps − 1)·spacing of SCENE), the worst frame's RMS distance, both runs'
estimated time errors (mean RMS over frames), the larger time error over the
distance, and both runs' CPU time. FIGURE_PNG: the distances as bars with both
time errors as marks.
Missing or malformed input: a message, exit 2, nothing written.
"""
import csv
import os
import sys
import tomllib

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "common"))
from runs import fail, save_figure  # noqa: E402


def rows_of(folder):
    """The reference's row (full) and the continuum's rows (fem_s*), in the file's order."""
    try:
        with open(os.path.join(folder, "fidelity.csv"), newline="", encoding="utf-8") as f:
            rows = list(csv.DictReader(f))
        full = [r for r in rows if r["variant"] == "full"]
        fem = [r for r in rows if r["variant"].startswith("fem_s")]
        if len(full) != 1 or not fem:
            raise KeyError("no row full or no row fem_s*")
        return full[0], fem
    except (OSError, KeyError) as e:
        fail(f"{folder}: not a fidelity rung folder with the rows full and fem_s* ({e})")


def number(text):
    try:
        return float(text)
    except (TypeError, ValueError):
        return float("nan")


def main(argv):
    if len(argv) < 5 or any("=" not in a for a in argv[4:]):
        fail(__doc__)
    scene, table, figure = argv[1:4]
    try:
        with open(scene, "rb") as f:
            cloth = tomllib.load(f)["cloth"]
        side = (int(cloth["warps"]) - 1) * float(cloth["spacing_m"])
    except (OSError, ValueError, KeyError) as e:
        fail(f"{scene}: {e}")
    head = ["continuum", "stride", "rms_m", "share_of_cloth", "worst_frame_rms_m", "yarn_time_error_m",
            "continuum_time_error_m", "time_error_over_distance", "continuum_outcome", "yarn_cpu_s",
            "continuum_cpu_s"]
    rows = []
    for label, folder in (a.split("=", 1) for a in argv[4:]):
        yarn, fems = rows_of(folder)
        for fem in fems:
            d = number(fem["rms_m"])
            ey, ef = number(yarn["time_error_mean_rms_m"]), number(fem["time_error_mean_rms_m"])
            rows.append([label, int(fem["variant"][len("fem_s"):]), d, d / side, number(fem["worst_frame_rms_m"]), ey,
                         ef, max(ey, ef) / d, fem["outcome"], number(yarn["cpu_s"]), number(fem["cpu_s"])])
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(6, 3.6))
    labels = list(dict.fromkeys(r[0] for r in rows))
    for k, r in enumerate(rows):
        ax.bar(k, 1e3 * r[2], color=f"C{labels.index(r[0])}", width=0.6)
        ax.plot([k - 0.3, k + 0.3], [1e3 * r[6]] * 2, "k:", lw=1.5, label="continuum's time error" if k == 0 else None)
        ax.plot([k - 0.3, k + 0.3], [1e3 * r[5]] * 2, "k--", lw=1, label="yarn level's time error" if k == 0 else None)
    ax.set_xticks(range(len(rows)), [f"{r[0]}\nstride {r[1]}" for r in rows], fontsize=8)
    ax.set_ylabel("RMS distance to the yarn level [mm]")
    ax.set_yscale("log")
    ax.legend(fontsize=8)
    fig.tight_layout()
    tmp = table + ".tmp"
    with open(tmp, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(head)
        w.writerows([[f"{x:.6g}" if isinstance(x, float) else x for x in r] for r in rows])
    save_figure(fig, figure)
    os.replace(tmp, table)


if __name__ == "__main__":
    main(sys.argv)
