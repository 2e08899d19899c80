#!/usr/bin/python3
"""The woven partner of the knit in the knits study's uniaxial pull
(experiments/knits/, docs/models.md §11.8): a flat plain weave with the knit
scene's yarn (its radius and [yarn_types.default]) whose n × n crossings at
spacing L give it the knit's yarn length per area ρ = 2n / ((n − 1) L), about
the knit patch's size (n = max(5, round(size ρ / 2) + 1), size the pull's grip
distance), no gravity, sliding on.

    woven_scene.py KNIT_SCENE KNIT_PULL_JSON OUT

KNIT_PULL_JSON is the knit's pull.json (`weavelab pull`: yarn_length_per_area_per_m,
grip_distance_m). Bad input: a message on stderr, exit status 2, nothing written.
"""
import json
import os
import sys
import tomllib


def fail(message):
    print(f"woven_scene.py: {message}", file=sys.stderr)
    sys.exit(2)


def main():
    if len(sys.argv) != 4:
        fail("usage: woven_scene.py KNIT_SCENE KNIT_PULL_JSON OUT")
    scene_path, pull_path, out = sys.argv[1:]
    try:
        with open(scene_path, "rb") as f:
            knit = tomllib.load(f)
        with open(pull_path, encoding="utf-8") as f:
            pull = json.load(f)
    except (OSError, ValueError) as e:
        fail(str(e))
    try:
        rho, size = float(pull["yarn_length_per_area_per_m"]), float(pull["grip_distance_m"])
        radius = knit["cloth"]["radius_m"]
        yarn = knit["yarn_types"]["default"]
        keys = {k: yarn[k] for k in ("density_kg_per_m", "stretch_modulus_Pa", "bending_modulus_Pa")}
    except KeyError as e:
        fail(f"{scene_path} / {pull_path}: no {e}")
    n = max(5, round(size * rho / 2.0) + 1)
    spacing = 2.0 * n / ((n - 1) * rho)
    text = (f"# A flat plain weave with the yarn of {os.path.basename(scene_path)} and its yarn length per area\n"
            f"# (experiments/knits/scripts/woven_scene.py).\n[cloth]\nwarps = {n}\nwefts = {n}\n"
            f"spacing_m = {spacing!r}\nradius_m = {radius!r}\nsliding = true\n\n[yarn_types.default]\n"
            + "".join(f"{k} = {v!r}\n" for k, v in keys.items())
            + '\n[pose]\nkind = "flat"\n\n[gravity]\nacceleration_m_per_s2 = [0.0, 0.0, 0.0]\n')
    with open(out + ".tmp", "w", encoding="utf-8") as f:
        f.write(text)
    os.replace(out + ".tmp", out)


if __name__ == "__main__":
    main()
