#!/usr/bin/python3
"""Concatenates CSV files with the same header into one (header once).
Usage: concat_csv.py OUT IN... ; a differing header: exit 2, nothing written."""
import os
import sys


def main(out, inputs):
    header, lines = None, []
    for path in inputs:
        with open(path, encoding="utf-8") as f:
            rows = f.read().splitlines()
        if not rows:
            sys.exit(f"concat_csv.py: error: {path}: empty, expected a header line")
        if header is not None and rows[0] != header:
            print(f"concat_csv.py: error: {path}: header '{rows[0]}' differs from '{header}' of {inputs[0]}",
                  file=sys.stderr)
            sys.exit(2)
        header = rows[0]
        lines += rows[1:]
    with open(out + ".tmp", "w", encoding="utf-8") as f:
        f.write("\n".join([header] + lines) + "\n")
    os.replace(out + ".tmp", out)


if __name__ == "__main__":
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2:])
