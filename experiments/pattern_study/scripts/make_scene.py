#!/usr/bin/python3
"""Writes the scene of one fabric of the pattern study: the hanging-cloth scene
with its weave pattern and hybrid yarn pair replaced (docs/models.md §8.1-§8.2).
Usage: make_scene.py PATTERN PAIR OUT, PATTERN in plain/twill/satin, PAIR in 12/13/23.
"""
import re
import sys

YARNS = {  # density kg/m, stretch modulus Pa, bending modulus Pa (docs/models.md §8.2)
    "1": (0.0020, 500000.0, 0.00014),
    "2": (0.0025, 170000.0, 0.00011),
    "3": (0.0024, 120000.0, 0.00009),
}
PATTERNS = {
    "plain": 'kind = "plain"\n',
    "twill": 'kind = "twill"\nover = 2\nunder = 2\nshift = 1\n',
    "satin": 'kind = "satin"\nharness = 5\nstep = 2\n',
}


def main(pattern, pair, out, base):
    text = open(base).read()
    text = re.sub(r"\A(#[^\n]*\n)+", "", text)  # the base scene's own header
    a, b = pair[0], pair[1]
    types = f'["yarn{a}", "yarn{b}"]'
    text = re.sub(r"^warp_yarn_types = .*$", f"warp_yarn_types = {types}", text, flags=re.M)
    text = re.sub(r"^weft_yarn_types = .*$", f"weft_yarn_types = {types}", text, flags=re.M)
    text = re.sub(r"\[cloth\.pattern\]\n(?:[^\[\n][^\n]*\n)*", "[cloth.pattern]\n" + PATTERNS[pattern] + "\n", text)
    yarns = ""
    for y in (a, b):
        rho, ys, bs = YARNS[y]
        yarns += (f"[yarn_types.yarn{y}]\ndensity_kg_per_m = {rho}\nstretch_modulus_Pa = {ys}\n"
                  f"bending_modulus_Pa = {bs}\n\n")
    text = re.sub(r"(\[yarn_types\.yarn\d\]\n(?:[^\[\n][^\n]*\n|\n)*)+", yarns, text)
    header = f"# Pattern study fabric: {pattern.capitalize()}-({a},{b}), generated from hanging_wind.toml.\n"
    with open(out, "w") as f:
        f.write(header + text)


if __name__ == "__main__":
    if len(sys.argv) != 5 or sys.argv[1] not in PATTERNS or sys.argv[2] not in ("12", "13", "23"):
        sys.exit("usage: make_scene.py plain|twill|satin 12|13|23 OUT BASE_SCENE")
    main(*sys.argv[1:])
