#!/usr/bin/python3
"""A continuum parameter file with one stiffness multiplied by a factor.

    scale_parameter.py PARAMS KEY FACTOR OUT

Copies PARAMS (a params.toml of `weavelab calibrate`) to OUT with the line
`KEY = VALUE` replaced by `KEY = VALUE * FACTOR` at full precision; every other
line (the provenance) stays. Bad input: a message, exit 2, nothing written.
"""
import os
import re
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "common"))
from runs import fail, write_text_atomically  # noqa: E402


def main(argv):
    if len(argv) != 4:
        fail(__doc__.strip().split("\n\n")[1].strip())
    params, key, factor_text, out = argv
    try:
        factor = float(factor_text)
    except ValueError:
        fail(f"FACTOR: got '{factor_text}', expected a number")
    try:
        with open(params, encoding="utf-8") as f:
            lines = f.read().splitlines()
    except OSError as e:
        fail(f"{params}: {e.strerror}")
    pattern = re.compile(rf"^{re.escape(key)}\s*=\s*(\S+)\s*$")
    found = [i for i, line in enumerate(lines) if pattern.match(line)]
    if len(found) != 1:
        fail(f"{params}: expected one line '{key} = VALUE', found {len(found)}")
    value_text = pattern.match(lines[found[0]]).group(1)
    try:
        value = float(value_text)
    except ValueError:
        fail(f"{params}:{found[0] + 1}: {key}: got '{value_text}', expected a number")
    lines[found[0]] = f"{key} = {value * factor!r}"
    write_text_atomically(out, "\n".join(lines) + "\n")


if __name__ == "__main__":
    main(sys.argv[1:])
