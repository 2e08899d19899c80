#!/usr/bin/python3
"""The bending length of the cantilever study (experiments/cantilever/,
docs/models.md §3.11): per model, the overhang l at which the line from the
ledge's edge to the strip's tip first falls 41.5° below the horizontal, and the
measured bending length c = 0.509 l (Peirce: (cos(θ/2) / (8 tan θ))^(1/3) l);
the prediction c = (G/W)^(1/3) from the continuum's warp bending stiffness G
[N·m] and its weight per area W = ρ_A g, as `weavelab info --model fem` states
them (warp_bending_N_m, areal_density_kg_per_m2).

    bending_length.py SCENE INFO --run MODEL=RUN [--run ...] --out CSV --prediction CSV

Writes one row per model (model, overhang_mm, time_s, bending_length_mm,
from_prediction_pct; empty cells when the tip never fell to 41.5°) and the
prediction (warp_bending_N_m, weight_N_per_m2, predicted_mm).
Missing or malformed inputs: a message on stderr and exit status 2.
"""
import argparse
import csv
import math
import os
import re
import sys
import tomllib

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "common"))
import runs as io  # noqa: E402

THETA = math.radians(41.5)
PEIRCE = (math.cos(THETA / 2) / (8 * math.tan(THETA))) ** (1 / 3)


def prediction(scene, info_path):
    """(G [N·m], W [N/m²], c = (G/W)^(1/3) [m]) from `weavelab info --model fem`."""
    try:
        with open(info_path, encoding="utf-8") as f:
            facts = dict(re.findall(r"(\w+)=([0-9.eE+-]+)", f.read()))
    except OSError as e:
        raise io.RunError(f"cannot read '{info_path}': {e}") from e
    missing = [k for k in ("warp_bending_N_m", "areal_density_kg_per_m2") if k not in facts]
    if missing:
        raise io.RunError(f"'{info_path}': no {', '.join(missing)} (the output of `weavelab info --model fem`)")
    g = -scene["gravity"]["acceleration_m_per_s2"][2]
    bending, weight = float(facts["warp_bending_N_m"]), float(facts["areal_density_kg_per_m2"]) * g
    return bending, weight, (bending / weight) ** (1 / 3)


def overhang_at_angle(scene, run):
    """(overhang [m], time [s]) at the first frame pair whose edge-to-tip angle crosses 41.5°, or None."""
    ledge = scene["obstacles"][0]
    edge0 = ledge["center_m"][0] + ledge["half_extents_m"][0]
    speed = -ledge["velocity_m_per_s"][0]
    top = ledge["center_m"][2] + ledge["half_extents_m"][2]
    nu, nv = scene["cloth"]["wefts"], scene["cloth"]["warps"]
    length = (nu - 1) * scene["cloth"]["spacing_m"]
    prev = None
    for t, mesh in io.read_frames(run):
        tip = mesh.points.reshape(nv, nu, 3)[nv // 2][-1]  # the middle warp's tip
        edge = edge0 - speed * t
        if tip[0] <= edge:
            continue
        angle = math.atan2(top - tip[2], tip[0] - edge)
        overhang = length - edge
        if prev and prev[0] < THETA <= angle:
            f = (THETA - prev[0]) / (angle - prev[0])
            return (1 - f) * prev[1] + f * overhang, t
        prev = (angle, overhang)
    return None


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("scene")
    ap.add_argument("info")
    ap.add_argument("--run", action="append", required=True, metavar="MODEL=RUN")
    ap.add_argument("--out", required=True)
    ap.add_argument("--prediction", required=True)
    a = ap.parse_args()
    try:
        with open(a.scene, "rb") as f:
            scene = tomllib.load(f)
    except (OSError, tomllib.TOMLDecodeError) as e:
        raise io.RunError(f"cannot read the scene '{a.scene}': {e}") from e
    bending, weight, predicted = prediction(scene, a.info)
    print(f"predicted c = (G/W)^(1/3) = {predicted * 1e3:.2f} mm (G = {bending:.4g} N m, W = {weight:.4g} N/m2)")
    rows = []
    for item in a.run:
        if "=" not in item:
            raise io.RunError(f"--run '{item}': expected MODEL=RUN")
        model, run = item.split("=", 1)
        found = overhang_at_angle(scene, run)
        if not found:
            print(f"{model}: the tip never fell to 41.5 degrees")
            rows.append([model, "", "", "", ""])
            continue
        c = PEIRCE * found[0]
        print(f"{model}: overhang at 41.5 deg {found[0] * 1e3:.2f} mm (t = {found[1]:.2f} s), "
              f"c = {c * 1e3:.2f} mm, {100 * (c / predicted - 1):+.1f} % from the prediction")
        rows.append([model, f"{found[0] * 1e3:.6g}", f"{found[1]:.6g}", f"{c * 1e3:.6g}",
                     f"{100 * (c / predicted - 1):.4g}"])
    with open(a.out, "w", newline="", encoding="utf-8") as f:
        w = csv.writer(f, lineterminator="\n")
        w.writerow(["model", "overhang_mm", "time_s", "bending_length_mm", "from_prediction_pct"])
        w.writerows(rows)
    with open(a.prediction, "w", newline="", encoding="utf-8") as f:
        w = csv.writer(f, lineterminator="\n")
        w.writerow(["warp_bending_N_m", "weight_N_per_m2", "predicted_mm"])
        w.writerow([f"{bending:.6g}", f"{weight:.6g}", f"{predicted * 1e3:.6g}"])


if __name__ == "__main__":
    try:
        main()
    except io.RunError as e:
        io.fail(str(e))
