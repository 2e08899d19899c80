#!/usr/bin/python3
"""Writes a scene variant: the base scene's text with a [compat] table of the given lines.

    make_variant.py BASE.toml OUT.toml [LINE ...]

No line: the base scene unchanged (the lab's default model). Exit 2 on a missing base scene or a
base scene that already has a [compat] table.
"""
import os
import sys


def main():
    if len(sys.argv) < 3:
        print(__doc__, file=sys.stderr)
        sys.exit(2)
    base, out, lines = sys.argv[1], sys.argv[2], sys.argv[3:]
    if not os.path.isfile(base):
        print(f"make_variant.py: error: base scene '{base}' is missing", file=sys.stderr)
        sys.exit(2)
    with open(base, encoding="utf-8") as f:
        text = f.read()
    if "[compat]" in text:
        print(f"make_variant.py: error: '{base}' already has a [compat] table", file=sys.stderr)
        sys.exit(2)
    if lines:
        text = text.rstrip("\n") + "\n\n[compat]   # docs/published_code.md\n" + "\n".join(lines) + "\n"
    os.makedirs(os.path.dirname(os.path.abspath(out)), exist_ok=True)
    with open(out + ".tmp", "w", encoding="utf-8") as f:
        f.write(text)
    os.replace(out + ".tmp", out)


if __name__ == "__main__":
    main()
