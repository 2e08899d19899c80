#!/usr/bin/python3
"""The Cusick drapes at their last frame (experiments/cusick/): per scene and
model, from drape_measure.py's per-frame table (with --state) and the run's
summary.json: the time, drape coefficient and folds at the last frame, the
kinetic energy there, the intersecting triangle pairs at the last frame and the
most over the frames, the closest node to the pedestal over the frames, the
steps and the rejected (retaken) ones, and the run's CPU time; beside them the
drape coefficient and folds `weavelab run` measured on its last frame (summary.json
"measures" "drape", from a scene with [measures] drape = true; empty otherwise),
a check of the two measures against each other.

    drape_table.py --drape SCENE:MODEL:RUN:CSV [...] --out CSV

Missing or malformed inputs: a message on stderr and exit status 2.
"""
import argparse
import csv
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "common"))
import runs as io  # noqa: E402

HEADER = ["scene", "model", "time_s", "drape_coefficient", "folds", "kinetic_J", "intersecting_pairs_at_end",
          "intersecting_pairs_most", "closest_to_pedestal_m", "steps", "rejected_steps", "cpu_s",
          "run_drape_coefficient", "run_folds"]


def read_frames_table(path):
    try:
        with open(path, newline="", encoding="utf-8") as f:
            rows = list(csv.DictReader(f))
    except OSError as e:
        raise io.RunError(f"cannot read '{path}': {e}") from e
    if not rows or "kinetic_J" not in rows[0]:
        raise io.RunError(f"'{path}': no rows with a kinetic_J column (drape_measure.py --state writes them)")
    return rows


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--drape", nargs="+", required=True, metavar="SCENE:MODEL:RUN:CSV")
    ap.add_argument("--out", required=True)
    a = ap.parse_args()
    out = []
    for item in a.drape:
        parts = item.split(":")
        if len(parts) != 4:
            raise io.RunError(f"--drape '{item}': expected SCENE:MODEL:RUN:CSV")
        scene, model, run, table = parts
        rows = read_frames_table(table)
        last = rows[-1]
        summary = io.read_summary(run, required=True)
        stats = summary.get("statistics", {})
        measured = (summary.get("measures") or {}).get("drape") or {}
        pairs = [int(r["intersecting_triangle_pairs"]) for r in rows]
        out.append([scene, model, last["time_s"], last["drape_coefficient"], last["folds"], last["kinetic_J"],
                    last["intersecting_triangle_pairs"], max(pairs),
                    f"{min(float(r['closest_to_pedestal_m']) for r in rows):.6g}", stats.get("steps", ""),
                    stats.get("rejected_steps", ""), f"{stats.get('cpu_s', float('nan')):.4g}",
                    measured.get("coefficient", ""), measured.get("folds", "")])
    with open(a.out, "w", newline="", encoding="utf-8") as f:
        w = csv.writer(f, lineterminator="\n")
        w.writerow(HEADER)
        w.writerows(out)


if __name__ == "__main__":
    try:
        main()
    except io.RunError as e:
        io.fail(str(e))
