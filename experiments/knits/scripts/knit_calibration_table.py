#!/usr/bin/env python3
"""Table of knit calibrations (the knits study, experiments/knits/): per scene, each
test curve's residual as % of its range for every law fitted (one
`weavelab calibrate` folder per law, named SCENE_LAW_RESIDUALS), with R(0), the
response the knit's rest shape holds on the ring at zero load, as % of the range.
Usage: knit_calibration_table.py DIR
"""
import json
import os
import sys
from collections import OrderedDict


def main(root):
    runs = OrderedDict()
    for name in sorted(os.listdir(root)):
        path = os.path.join(root, name, "calibration.json")
        if os.path.isfile(path):
            with open(path) as f:
                runs[name] = json.load(f)
    scenes = OrderedDict()
    for name, c in runs.items():
        scene, law = name.split("_", 1)
        scenes.setdefault(scene, OrderedDict())[law] = c
    for scene, laws in scenes.items():
        first = next(iter(laws.values()))
        print(f"\n{scene}, patch {first['patch']} × {first['patch']}, sliding {str(first['sliding']).lower()}\n")
        names = [law + ("" if c["fit"]["converged"] else " (not converged)") for law, c in laws.items()]
        print("| test | R(0) [% of range] | " + " | ".join(names) + " |")
        print("|---|---|" + "---|" * len(laws))
        for k, t in enumerate(first["tests"]):
            cells = []
            for c in laws.values():
                rms = c["tests"][k]["residual_rms_relative"]
                cells.append(f"{100 * rms:.2f} %")
            print(f"| {t['test']} | {100 * t['response_at_rest_relative']:.2f} | " + " | ".join(cells) + " |")
        worst = {law: max(t["residual_rms_relative"] for t in c["tests"]) for law, c in laws.items()}
        print("\nworst curve: " + ", ".join(f"{law} {100 * w:.2f} %" for law, w in worst.items()))
        reached = [law for law, w in worst.items() if w <= 0.05]
        print("laws within 5 % of every curve's range: " + (", ".join(reached) if reached else "none"))


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(sys.argv[1])
