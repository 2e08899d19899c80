#!/usr/bin/python3
"""The cloth on the sphere against the same scene without it (experiments/obstacles/,
docs/models.md §3.11), per model: the closest any node came to the sphere over
the frames (‖x − c‖ − r) and the vertical contact force on the cloth at the last
frame (point data contact_force), then the median step wall time with and without
the sphere and their ratio, the mean CPU time per step (summary.json's total over
the steps) and its ratio, the steps and the rejected (retaken) steps.

    contact_cost.py SCENE --runs MODEL:WITH:WITHOUT [...] --contact CSV --cost CSV

SCENE is the sphere scene (its first obstacle is the sphere); WITH and WITHOUT
are the run folders with and without it.
Missing or malformed inputs: a message on stderr and exit status 2.
"""
import argparse
import csv
import os
import statistics
import sys
import tomllib

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "common"))
import runs as io  # noqa: E402


def write_csv(path, header, rows):
    with open(path, "w", newline="", encoding="utf-8") as f:
        w = csv.writer(f, lineterminator="\n")
        w.writerow(header)
        w.writerows(rows)


def sphere_of(scene_path):
    try:
        with open(scene_path, "rb") as f:
            sphere = tomllib.load(f)["obstacles"][0]
    except (OSError, tomllib.TOMLDecodeError, KeyError, IndexError) as e:
        raise io.RunError(f"'{scene_path}': no readable first obstacle ({e})") from e
    if sphere.get("shape") != "sphere":
        raise io.RunError(f"'{scene_path}': the first obstacle is a {sphere.get('shape')}, expected a sphere")
    return np.array(sphere["center_m"]), sphere["radius_m"]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("scene")
    ap.add_argument("--runs", nargs="+", required=True, metavar="MODEL:WITH:WITHOUT")
    ap.add_argument("--contact", required=True)
    ap.add_argument("--cost", required=True)
    a = ap.parse_args()
    center, radius = sphere_of(a.scene)
    contact, cost = [], []
    for item in a.runs:
        parts = item.split(":")
        if len(parts) != 3:
            raise io.RunError(f"--runs '{item}': expected MODEL:WITH:WITHOUT")
        model, with_run, without_run = parts
        frames = io.read_frames(with_run)
        closest = min((np.linalg.norm(m.points - center, axis=1) - radius).min() for _, m in frames)
        force = io.point_array(frames[-1][1], "contact_force", with_run)[:, 2].sum()
        contact.append([model, f"{closest:.6g}", f"{force:.6g}"])
        times = {r: io.step_wall_times(io.read_metrics(r), r) for r in (with_run, without_run)}
        stats = {r: io.read_summary(r, required=True).get("statistics", {}) for r in (with_run, without_run)}
        w, wo = statistics.median(times[with_run]), statistics.median(times[without_run])
        cpu = {r: stats[r]["cpu_s"] / stats[r]["steps"] for r in (with_run, without_run)}
        cost.append([model, f"{1e3 * w:.6g}", f"{1e3 * wo:.6g}", f"{w / wo:.4g}", f"{1e3 * cpu[with_run]:.6g}",
                     f"{1e3 * cpu[without_run]:.6g}", f"{cpu[with_run] / cpu[without_run]:.4g}", len(times[with_run]),
                     len(times[without_run]), stats[with_run].get("rejected_steps", 0),
                     stats[with_run].get("factorizations", ""), stats[without_run].get("factorizations", ""),
                     stats[with_run].get("krylov_iters", ""), stats[without_run].get("krylov_iters", "")])
    write_csv(a.contact, ["model", "closest_node_to_sphere_m", "contact_force_z_at_end_N"], contact)
    write_csv(a.cost, ["model", "median_step_with_ms", "median_step_without_ms", "ratio", "mean_cpu_per_step_with_ms",
                       "mean_cpu_per_step_without_ms", "ratio_cpu", "steps_with",
                       "steps_without", "rejected_with", "factorizations_with", "factorizations_without",
                       "gmres_iterations_with", "gmres_iterations_without"], cost)


if __name__ == "__main__":
    try:
        main()
    except io.RunError as e:
        io.fail(str(e))
