"""Merges the jobs of the fidelity workflow (experiments/fidelity/Snakefile)
into the fidelity.csv and fidelity.json one `weavelab fidelity` run writes:
the reference's row from the reference job, each rung's row from its job (the
reference row each rung job carries is dropped), and what depends on all rows
computed again over them by the rules of driver/fidelity.h: the
Pareto front of (CPU time, worst-frame RMS distance) among the complete rows,
and the cheapest rung within each tolerance whose own time error is within it
too, with its speed-up over the reference.

    /usr/bin/python3 experiments/common/merge_fidelity.py OUT REFERENCE_DIR RUNG_DIR...

Files are written under a temporary name and renamed. A missing or malformed
job folder: a message naming it and exit 2, nothing written.
"""
import csv
import io
import json
import os
import sys


def write_atomically(path, text):
    with open(path + ".tmp", "w", encoding="utf-8", newline="") as f:
        f.write(text)
    os.replace(path + ".tmp", path)


def fail(message):
    print(f"merge_fidelity.py: error: {message}", file=sys.stderr)
    sys.exit(2)


def read_part(folder):
    try:
        with open(os.path.join(folder, "fidelity.json"), encoding="utf-8") as f:
            summary = json.load(f)
        with open(os.path.join(folder, "fidelity.csv"), newline="", encoding="utf-8") as f:
            table = list(csv.reader(f))
    except (OSError, ValueError) as e:
        fail(f"{folder}: not the folder of a `weavelab fidelity` job ({e})")
    if "variants" not in summary or len(table) != len(summary["variants"]) + 1:
        fail(f"{folder}: fidelity.csv and fidelity.json hold different rows")
    return summary, table[0], table[1:]


def complete(row):
    return row["outcome"] == "ok" and (row.get("compared_fraction") or 0) > 0


def pareto_front(points):
    """on_front[i] when no other point has cost <= and error <= with one strictly smaller."""
    front = []
    for i, (ci, ei) in enumerate(points):
        front.append(not any(j != i and cj <= ci and ej <= ei and (cj < ci or ej < ei)
                             for j, (cj, ej) in enumerate(points)))
    return front


def cheapest_within(rows, tolerance, cloth_size):
    best = None
    for r in rows:
        worst, own = r.get("worst_frame_rms_m"), (r.get("time_error") or {}).get("worst_frame_rms_m")
        if complete(r) and worst is not None and worst <= tolerance and not (own is not None and own > tolerance):
            if best is None or r["cpu_s"] < best["cpu_s"]:
                best = r
    choice = {"tolerance_m": tolerance, "tolerance_of_cloth_size": tolerance / cloth_size,
              "variant": "", "cpu_s": 0.0, "speedup_over_reference": 0.0}
    if best is not None:
        choice.update(variant=best["variant"], cpu_s=best["cpu_s"],
                      speedup_over_reference=rows[0]["cpu_s"] / best["cpu_s"] if best["cpu_s"] > 0 else None)
    return choice


def merge(reference_dir, rung_dirs):
    summary, header, table = read_part(reference_dir)
    rows, lines = [summary["variants"][0]], [table[0]]
    parts = [{"folder": reference_dir, "wall_s": summary["wall_s"]}]
    for folder in rung_dirs:
        part, part_header, part_table = read_part(folder)
        if part_header != header:
            fail(f"{folder}: columns {part_header} differ from {header}")
        if part["scene_hash"] != summary["scene_hash"] or part["reference"] != summary["reference"]:
            fail(f"{folder}: another scene or reference than {reference_dir}")
        rows += part["variants"][1:]
        lines += part_table[1:]
        parts.append({"folder": folder, "wall_s": part["wall_s"]})

    ok = [i for i, r in enumerate(rows) if complete(r)]
    front = pareto_front([(rows[i]["cpu_s"], rows[i]["worst_frame_rms_m"]) for i in ok])
    for r in rows:
        r["on_front"] = False
    for i, on in zip(ok, front):
        rows[i]["on_front"] = on
    column = header.index("on_front")
    for r, line in zip(rows, lines):
        line[column] = "1" if r["on_front"] else "0"

    cloth = summary["cloth_size_m"]
    for key in ("cheapest_within_tolerance", "cheapest_within_1_percent", "cheapest_within_5_percent"):
        summary[key] = cheapest_within(rows, summary[key]["tolerance_m"], cloth)
    summary["variants"] = rows
    summary["wall_s"] = sum(p["wall_s"] for p in parts)
    summary["wall_s_meaning"] = "sum over the workflow's jobs (the reference and one job per rung)"
    summary["parts"] = parts
    text = io.StringIO()
    csv.writer(text, lineterminator="\n").writerows([header] + lines)
    return summary, text.getvalue()


def main():
    if len(sys.argv) < 3:
        print(__doc__, file=sys.stderr)
        sys.exit(2)
    out, reference_dir, rung_dirs = sys.argv[1], sys.argv[2], sys.argv[3:]
    summary, table = merge(reference_dir, rung_dirs)
    os.makedirs(out, exist_ok=True)
    write_atomically(os.path.join(out, "fidelity.csv"), table)
    write_atomically(os.path.join(out, "fidelity.json"), json.dumps(summary, indent=2) + "\n")


if __name__ == "__main__":
    main()
