#!/usr/bin/python3
"""A scene with a [fem] table added: the shipped scene's text, then the keys.

    make_scene.py BASE OUT KEY=VALUE ...

VALUE is a TOML value as written in a scene (true, "spline", [0.1, 0.2]).
The base scene must have no [fem] table of its own (the keys would be defined
twice). Writes OUT (under a temporary name, then renamed); bad input: a
message naming the file or the pair, exit 2, nothing written.
"""
import os
import sys
import tomllib

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "common"))
from runs import fail, write_text_atomically  # noqa: E402


def fem_lines(pairs):
    lines = []
    for pair in pairs:
        key, sep, value = pair.partition("=")
        if not sep or not key.strip() or not value.strip():
            fail(f"'{pair}': expected KEY=VALUE (a [fem] key and a TOML value)")
        try:
            tomllib.loads(f"x = {value.strip()}")
        except tomllib.TOMLDecodeError as e:
            fail(f"'{pair}': the value is not TOML ({e})")
        lines.append(f"{key.strip()} = {value.strip()}")
    return lines


def main(argv):
    if len(argv) < 3:
        fail(__doc__.strip().split("\n\n")[1].strip())
    base, out, pairs = argv[0], argv[1], argv[2:]
    try:
        with open(base, encoding="utf-8") as f:
            text = f.read()
        scene = tomllib.loads(text)
    except OSError as e:
        fail(f"{base}: {e.strerror}")
    except tomllib.TOMLDecodeError as e:
        fail(f"{base}: not TOML ({e})")
    if "fem" in scene:
        fail(f"{base}: has a [fem] table of its own; expected a scene without one")
    os.makedirs(os.path.dirname(out) or ".", exist_ok=True)
    write_text_atomically(out, text.rstrip("\n") + "\n\n[fem]\n" + "\n".join(fem_lines(pairs)) + "\n")


if __name__ == "__main__":
    main(sys.argv[1:])
