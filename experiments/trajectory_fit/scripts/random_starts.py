#!/usr/bin/python3
"""The random starts of the trajectory-fit study, as in Gong et al. 2022's
Tables 6–7: each yarn parameter drawn uniformly within ±SPREAD of the two
yarns' mean, the contact's shear modulus and friction coefficient uniformly in
their ranges, from Python's random.Random(SEED), in a fixed order (so a seed
always gives the same start).

    random_starts.py SEED ...

prints one `--start-set` value (KEY=VALUE,KEY=VALUE,...) per seed with the
defaults below; the Snakefile calls start_set() with the config's values.
"""
import random
import sys

DEFAULT = {"shear_range": (500.0, 1200.0), "friction_range": (0.2, 0.8), "spread": 0.1, "yarns": ("yarn1", "yarn2"),
           "means": {"density_kg_per_m": 0.00225, "stretch_modulus_Pa": 335000.0, "bending_modulus_Pa": 0.000125}}


def start_set(seed, shear_range, friction_range, spread, yarns, means):
    """KEY=VALUE,... of one random start; `means` is ordered (its order is the draws')."""
    r = random.Random(int(seed))
    s = [f"contact.shear_modulus_Pa={r.uniform(*shear_range):.6g}",
         f"contact.friction_coefficient={r.uniform(*friction_range):.6g}"]
    for y in yarns:
        for key, mean in means.items():
            s.append(f"yarn_types.{y}.{key}={mean * r.uniform(1 - spread, 1 + spread):.6g}")
    return ",".join(s)


if __name__ == "__main__":
    if len(sys.argv) < 2 or not all(a.lstrip("-").isdigit() for a in sys.argv[1:]):
        print(f"{sys.argv[0]}: error: usage: random_starts.py SEED ... (integers)", file=sys.stderr)
        sys.exit(2)
    for seed in sys.argv[1:]:
        print(start_set(seed, **DEFAULT))
