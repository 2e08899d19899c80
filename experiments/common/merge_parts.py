"""Merges the parts of a sweep run cell by cell (experiments/*/Snakefile) into
the folder one `weavelab work-precision` or `weavelab stability` run would
write: every CSV of the parts concatenated under one header, and the parts'
JSON summaries as one: its parameter lists the union over the parts, its
objects keyed by model and its notes joined, its counts and wall times the
sums, each part's summary kept under "parts".

    /usr/bin/python3 experiments/common/merge_parts.py OUT NAME PART_DIR...

NAME is the experiment's file stem (stability, work_precision). Files are
written under a temporary name and renamed.
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


def merge_csv(paths):
    header, rows = None, []
    for path in paths:
        with open(path, newline="", encoding="utf-8") as f:
            reader = csv.reader(f)
            part_header = next(reader)
            if header is None:
                header = part_header
            elif part_header != header:
                sys.exit(f"merge_parts.py: {path}: columns {part_header} differ from {header}")
            rows.extend(reader)
    text = io.StringIO()
    writer = csv.writer(text, lineterminator="\n")
    writer.writerow(header)
    writer.writerows(rows)
    return text.getvalue()


def merge_json(summaries):
    merged = dict(summaries[0])
    params = dict(merged.get("parameters", {}))
    for key, value in list(params.items()):
        if isinstance(value, list):
            union = []
            for s in summaries:
                for item in s.get("parameters", {}).get(key, []):
                    if item not in union:
                        union.append(item)
            params[key] = union
    merged["parameters"] = params
    for key, value in list(merged.items()):  # objects keyed by model (work-precision "references")
        if key not in ("parameters", "scene") and isinstance(value, dict):
            merged[key] = {k: v for s in summaries for k, v in s.get(key, {}).items()}
        elif key == "notes" and isinstance(value, list):
            merged[key] = [n for s in summaries for n in s.get(key, [])]
    for key in ("cells", "runs"):
        if isinstance(merged.get(key), int):
            merged[key] = sum(s.get(key, 0) for s in summaries)
    if "wall_s" in merged:
        merged["wall_s"] = sum(s.get("wall_s", 0.0) for s in summaries)
        merged["wall_s_meaning"] = "sum over the parts (each one job of the workflow)"
    merged["started_utc"] = min(s.get("started_utc", "") for s in summaries)
    merged["finished_utc"] = max(s.get("finished_utc", "") for s in summaries)
    merged["parts"] = summaries
    return merged


def main():
    if len(sys.argv) < 4:
        sys.exit(__doc__)
    out, name, parts = sys.argv[1], sys.argv[2], sys.argv[3:]
    os.makedirs(out, exist_ok=True)
    csv_names = sorted(f for f in os.listdir(parts[0]) if f.endswith(".csv"))
    for csv_name in csv_names:
        write_atomically(os.path.join(out, csv_name), merge_csv([os.path.join(p, csv_name) for p in parts]))
    summaries = []
    for p in parts:
        with open(os.path.join(p, name + ".json"), encoding="utf-8") as f:
            summaries.append(json.load(f))
    write_atomically(os.path.join(out, name + ".json"), json.dumps(merge_json(summaries), indent=2) + "\n")


if __name__ == "__main__":
    main()
