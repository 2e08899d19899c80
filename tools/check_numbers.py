#!/usr/bin/python3
"""Check that README.md and docs/ retype no measured number.

A measured figure (a timing, a speed-up, a distance from a run, a memory peak,
an iteration count with its unit) lives in one place: the RESULTS.md that its
study writes (experiments/<study>/RESULTS.md). The README and the docs link to
it. This script scans README.md and docs/**/*.md for a number followed by a
unit and fails on each one that is neither

- inside the generated block of the README, between the markers
  `<!-- results-index:start -->` and `<!-- results-index:end -->`, nor
- covered by an entry of the allow-list (tools/check_numbers_allow.txt): model
  constants, defaults of the interface, figures published in a paper.

Allow-list format, one entry per line, `#` starts a comment line:

    TEXT :: REASON

An entry allows every hit that lies inside an occurrence of TEXT on the line
(so TEXT is the number with its unit and as much context as makes it unique).
REASON is required: why the figure is not a measurement of this lab. An entry
that no scanned line uses is reported too, so the list cannot rot.

Usage: check_numbers.py [--root DIR] [--allow FILE] [FILE ...]
Exit 0 when clean, 1 listing `file:line: text` for each hit, 2 on bad input.
"""
import argparse
import glob
import os
import re
import sys

START = "<!-- results-index:start -->"
END = "<!-- results-index:end -->"

# Units a measurement of this lab carries: times, lengths, memory, frequencies,
# energies, ratios. Longer spellings first, so `mm` wins over `m`. Letter units
# follow their number after a space (as the docs write them; `2s` in a formula
# is no unit); `%` and `×` may be attached, `x` must be.
WORD_UNITS = [
    "ns", "µs", "us", "ms", "min", "s", "h",
    "nm", "µm", "um", "mm", "cm", "m/s", "m",
    "TB", "GB", "MB", "kB", "KB", "GiB", "MiB", "KiB",
    "kHz", "Hz",
    "µJ", "mJ", "J",
]
SYMBOL_UNITS = ["%", "×"]
# A number: digits with optional thin/normal-space or comma thousands groups,
# decimals, an exponent (e, or ·10⁻ⁿ). Not part of a name (x86, v3, §11, sha).
NUMBER = r"(?<![\w.§/#-])[-−+]?\d+(?:[  ,]\d{3})*(?:\.\d+)?(?:[eE][-+]?\d+|·10[⁻⁰¹²³⁴⁵⁶⁷⁸⁹]+)?"
WORD_UNIT = "|".join(re.escape(u) for u in WORD_UNITS)
SYMBOL_UNIT = "|".join(re.escape(u) for u in SYMBOL_UNITS)
# The unit ends the token: no letter or digit after it. `×` and `x` must not be
# a grid size (17×17, 16 × 16), and `x` follows its number without a space.
HIT = re.compile(
    r"(?P<number>" + NUMBER + r")"
    r"(?:(?P<attached>x)|[  ]?(?P<symbol>" + SYMBOL_UNIT + r")|[  ](?P<unit>" + WORD_UNIT + r"))"
    r"(?![\w])(?!\s?\d)"
)


def bad_input(message):
    """Exit 2 with the message on stderr (the project's code for bad input)."""
    print(f"check_numbers: {message}", file=sys.stderr)
    sys.exit(2)


def read_allow_list(path):
    """Entries (text, reason) of the allow-list; exit 2 on a malformed line."""
    entries = []
    with open(path, encoding="utf-8") as f:
        for number, line in enumerate(f, 1):
            line = line.rstrip("\n")
            if not line.strip() or line.lstrip().startswith("#"):
                continue
            text, sep, reason = line.partition(" :: ")
            if not sep or not text.strip() or not reason.strip():
                bad_input(f"{path}:{number}: expected 'TEXT :: REASON', got {line!r}")
            entries.append((text.strip(), reason.strip()))
    return entries


def hits_in_line(line):
    """Spans (start, end, text) of the numbers with a unit on one line."""
    found = []
    for match in HIT.finditer(line):
        found.append((match.start(), match.end(), match.group(0)))
    return found


def allowed(line, start, end, entries, used):
    """Whether an allow-list entry's occurrence on the line covers the span."""
    for index, (text, _) in enumerate(entries):
        position = line.find(text)
        while position >= 0:
            if position <= start and end <= position + len(text):
                used.add(index)
                return True
            position = line.find(text, position + 1)
    return False


def scan(path, display, entries, used):
    """Problems `display:line: text` of one file."""
    problems = []
    inside_generated = False
    with open(path, encoding="utf-8") as f:
        for number, line in enumerate(f, 1):
            if START in line:
                inside_generated = True
            if inside_generated:
                if END in line:
                    inside_generated = False
                continue
            for start, end, text in hits_in_line(line):
                if not allowed(line, start, end, entries, used):
                    problems.append(f"{display}:{number}: '{text}' in: {line.strip()}")
    if inside_generated:
        problems.append(f"{display}: '{START}' without '{END}'")
    return problems


def default_files(root):
    files = [os.path.join(root, "README.md")]
    files += sorted(glob.glob(os.path.join(root, "docs", "**", "*.md"), recursive=True))
    return [f for f in files if os.path.isfile(f)]


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--root", default=os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."),
                        help="repository root (default: the folder above tools/)")
    parser.add_argument("--allow", help="allow-list (default ROOT/tools/check_numbers_allow.txt)")
    parser.add_argument("files", nargs="*", help="files to scan (default README.md and docs/**/*.md)")
    args = parser.parse_args(argv)
    root = os.path.abspath(args.root)
    allow_path = args.allow or os.path.join(root, "tools", "check_numbers_allow.txt")
    if not os.path.isfile(allow_path):
        bad_input(f"allow-list {allow_path}: no such file")
    entries = read_allow_list(allow_path)
    files = args.files or default_files(root)
    used = set()
    problems = []
    for path in files:
        if not os.path.isfile(path):
            bad_input(f"{path}: no such file")
        problems += scan(path, os.path.relpath(os.path.abspath(path), root), entries, used)
    if not args.files:
        for index, (text, _) in enumerate(entries):
            if index not in used:
                problems.append(f"{os.path.relpath(allow_path, root)}: entry '{text}' allows nothing: remove it")
    for problem in problems:
        print(problem)
    if problems:
        print(f"check_numbers: {len(problems)} measured number(s) typed by hand; a measured figure lives in "
              "the RESULTS.md of the study that measures it (link to it), a constant goes into the allow-list "
              "with its reason", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
