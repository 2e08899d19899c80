#!/usr/bin/python3
"""A study's variant of a scene: the scene's text with some keys set and,
optionally, its obstacles removed, written beside the study's runs.

    scene_variant.py SCENE OUT [--set TABLE.KEY=VALUE ...] [--unset TABLE.KEY ...] [--without-obstacles]

--set replaces the line `KEY = ...` of the table [TABLE] (a dotted TABLE such
as cloth.pattern names a nested table), adds it at the table's top when the
table has no such key, and appends the table when the scene has none. VALUE is
TOML as written in a scene: 0.1, true, "exact". --unset removes the key's line
from its table, so that the scene takes the key's default (a key the scene does
not set is left unset: e.g. a settling phase removed for a short run of a scene
that may or may not have one). --without-obstacles drops every
[[obstacles]] entry. The scene's comments and the order of its keys are kept.
The result is parsed back and each key checked, so that a key that did not take
is an error, not a silent run of the original scene.
Bad input: a message naming the scene, the key and the value on stderr, exit
status 2, and nothing written.
"""
import argparse
import os
import re
import sys
import tomllib


def fail(message):
    print(f"scene_variant.py: {message}", file=sys.stderr)
    sys.exit(2)


def parse_setting(text):
    if "=" not in text:
        fail(f"--set '{text}': expected TABLE.KEY=VALUE")
    path, value = (s.strip() for s in text.split("=", 1))
    if "." not in path:
        fail(f"--set '{text}': expected TABLE.KEY=VALUE (the key inside a table)")
    table, key = path.rsplit(".", 1)
    try:
        parsed = tomllib.loads(f"v = {value}")["v"]
    except tomllib.TOMLDecodeError as e:
        fail(f"--set '{text}': the value '{value}' is not TOML ({e})")
    return table, key, value, parsed


def without_obstacles(text):
    """The text with every [[obstacles]] entry (header to the next table) removed."""
    lines, kept, skipping = text.split("\n"), [], False
    for line in lines:
        header = re.match(r"^\s*\[\[?\s*([^\]]+?)\s*\]\]?", line)
        if header:
            skipping = line.lstrip().startswith("[[") and header.group(1) == "obstacles"
        if not skipping:
            kept.append(line)
    return "\n".join(kept)


def set_key(text, table, key, value):
    lines = text.split("\n")
    start = next((k for k, line in enumerate(lines) if re.match(rf"^\s*\[\s*{re.escape(table)}\s*\]\s*(#.*)?$", line)),
                 None)
    if start is None:
        return text.rstrip("\n") + f"\n\n[{table}]\n{key} = {value}\n"
    end = next((k for k in range(start + 1, len(lines)) if re.match(r"^\s*\[", lines[k])), len(lines))
    for k in range(start + 1, end):
        match = re.match(rf"^(\s*){re.escape(key)}\s*=\s*(\"[^\"]*\"|[^#]*?)(\s*#.*)?$", lines[k])
        if match:
            lines[k] = f"{match.group(1)}{key} = {value}{match.group(3) or ''}"
            return "\n".join(lines)
    lines.insert(start + 1, f"{key} = {value}")
    return "\n".join(lines)


def unset_key(text, table, key):
    lines = text.split("\n")
    start = next((k for k, line in enumerate(lines) if re.match(rf"^\s*\[\s*{re.escape(table)}\s*\]\s*(#.*)?$", line)),
                 None)
    if start is None:
        return text
    end = next((k for k in range(start + 1, len(lines)) if re.match(r"^\s*\[", lines[k])), len(lines))
    kept = [line for k, line in enumerate(lines)
            if not (start < k < end and re.match(rf"^\s*{re.escape(key)}\s*=", line))]
    return "\n".join(kept)


def lookup(scene, table, key):
    node = scene
    for part in table.split(".") + [key]:
        if not isinstance(node, dict) or part not in node:
            return None
        node = node[part]
    return node


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("scene")
    ap.add_argument("out")
    ap.add_argument("--set", action="append", default=[], metavar="TABLE.KEY=VALUE")
    ap.add_argument("--unset", action="append", default=[], metavar="TABLE.KEY")
    ap.add_argument("--without-obstacles", action="store_true")
    a = ap.parse_args()
    try:
        with open(a.scene, encoding="utf-8") as f:
            text = f.read()
    except OSError as e:
        fail(f"cannot read the scene '{a.scene}': {e}")
    settings = [parse_setting(s) for s in a.set]
    removals = []
    for path in a.unset:
        if "." not in path or "=" in path:
            fail(f"--unset '{path}': expected TABLE.KEY")
        removals.append(tuple(path.rsplit(".", 1)))
    if a.without_obstacles:
        text = without_obstacles(text)
    for table, key in removals:
        text = unset_key(text, table, key)
    for table, key, value, _ in settings:
        text = set_key(text, table, key, value)
    try:
        scene = tomllib.loads(text)
    except tomllib.TOMLDecodeError as e:
        fail(f"{a.scene} with {' '.join(a.set)}: not TOML any more ({e})")
    for table, key, value, parsed in settings:
        if lookup(scene, table, key) != parsed:
            fail(f"{a.scene}: {table}.{key} did not take the value {value}")
    for table, key in removals:
        if lookup(scene, table, key) is not None and (table, key) not in [(s[0], s[1]) for s in settings]:
            fail(f"{a.scene}: {table}.{key} is still set after --unset (is it written inline?)")
    if a.without_obstacles and "obstacles" in scene:
        fail(f"{a.scene}: obstacles left after --without-obstacles")
    os.makedirs(os.path.dirname(os.path.abspath(a.out)), exist_ok=True)
    with open(a.out + ".tmp", "w", encoding="utf-8") as f:
        f.write(text if text.endswith("\n") else text + "\n")
    os.replace(a.out + ".tmp", a.out)


if __name__ == "__main__":
    main()
