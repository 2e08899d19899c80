#!/usr/bin/python3
"""Writes a scene variant: the base scene's text with a [compat] table of the given lines.

    make_variant.py BASE.toml OUT.toml [--dt-s DT --duration-s T] [LINE ...]

No line: the base scene unchanged (the lab's default model). With --dt-s and --duration-s the
[time] keys dt_s, duration_s and output_interval_s (a frame every step) are replaced, for the
fine-step comparison. Exit 2 on a missing base scene, a base scene that already has a [compat]
table, a time key missing from it, or a step that is not positive or does not divide the duration.
"""
import argparse
import os
import re
import sys


def fail(message):
    print(f"make_variant.py: error: {message}", file=sys.stderr)
    sys.exit(2)


def set_time_key(text, base, key, value):
    """The line `key = ...` (its comment too, which described the old value) becomes `key = value`."""
    pattern = re.compile(rf"^{key}\s*=.*$", re.MULTILINE)
    if len(pattern.findall(text)) != 1:
        fail(f"'{base}': expected one line '{key} = ...' to replace")
    return pattern.sub(f"{key} = {value!r}", text, count=1)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("base")
    parser.add_argument("out")
    parser.add_argument("lines", nargs="*")
    parser.add_argument("--dt-s", type=float)
    parser.add_argument("--duration-s", type=float)
    args = parser.parse_intermixed_args()
    if not os.path.isfile(args.base):
        fail(f"base scene '{args.base}' is missing")
    with open(args.base, encoding="utf-8") as f:
        text = f.read()
    if "[compat]" in text:
        fail(f"'{args.base}' already has a [compat] table")
    if (args.dt_s is None) != (args.duration_s is None):
        fail("--dt-s and --duration-s go together")
    if args.dt_s is not None:
        steps = args.duration_s / args.dt_s if args.dt_s > 0 else 0.0
        if args.dt_s <= 0 or steps < 1 or abs(steps - round(steps)) > 1e-9 * steps:
            fail(f"--dt-s {args.dt_s} --duration-s {args.duration_s}: expected a positive step that divides "
                 "the duration")
        for key, value in (("duration_s", args.duration_s), ("dt_s", args.dt_s), ("output_interval_s", args.dt_s)):
            text = set_time_key(text, args.base, key, value)
    if args.lines:
        text = text.rstrip("\n") + "\n\n[compat]   # docs/published_code.md\n" + "\n".join(args.lines) + "\n"
    os.makedirs(os.path.dirname(os.path.abspath(args.out)), exist_ok=True)
    with open(args.out + ".tmp", "w", encoding="utf-8") as f:
        f.write(text)
    os.replace(args.out + ".tmp", args.out)


if __name__ == "__main__":
    main()
