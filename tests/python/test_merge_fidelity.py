"""The fidelity workflow's merge (experiments/common/merge_fidelity.py): the
rows of separate jobs become the files one `weavelab fidelity` run writes, the
Pareto front and the cheapest rung within each tolerance computed again by the
rules of one run; and a ladder run as jobs through the command line gives the
distances of one run bit for bit."""
import csv
import json
import os
import subprocess
import sys
import tempfile
import unittest

from support import CLI, SOURCE_DIR

MERGE = os.path.join(SOURCE_DIR, "experiments", "common", "merge_fidelity.py")
COLUMNS = ["variant", "model", "cpu_s", "worst_frame_rms_m", "time_error_worst_frame_rms_m", "outcome", "on_front"]


def row(variant, cpu, worst, own=None, outcome="ok"):
    r = {"variant": variant, "model": "yarn", "outcome": outcome, "cpu_s": cpu, "worst_frame_rms_m": worst,
         "compared_fraction": 1.0, "on_front": False}
    if own is not None:
        r["time_error"] = {"method": "richardson", "mean_rms_m": own / 2, "worst_frame_rms_m": own}
    return r


def write_part(folder, rows):
    """A job's folder: fidelity.json and fidelity.csv holding `rows` (the reference first)."""
    os.makedirs(folder)
    choice = {"tolerance_m": 0.0, "tolerance_of_cloth_size": 0.0, "variant": "", "cpu_s": 0.0,
              "speedup_over_reference": 0.0}
    summary = {"scene_hash": "abc", "reference": "full", "cloth_size_m": 0.1, "wall_s": 1.0, "variants": rows,
               "cheapest_within_tolerance": dict(choice, tolerance_m=0.001),
               "cheapest_within_1_percent": dict(choice, tolerance_m=0.001),
               "cheapest_within_5_percent": dict(choice, tolerance_m=0.005)}
    with open(os.path.join(folder, "fidelity.json"), "w") as f:
        json.dump(summary, f)
    with open(os.path.join(folder, "fidelity.csv"), "w", newline="") as f:
        w = csv.writer(f, lineterminator="\n")
        w.writerow(COLUMNS)
        for r in rows:
            w.writerow([r["variant"], r["model"], r["cpu_s"], r["worst_frame_rms_m"],
                        (r.get("time_error") or {}).get("worst_frame_rms_m", ""), r["outcome"], "0"])


class MergeFidelity(unittest.TestCase):
    def test_front_and_choices_are_computed_over_all_jobs(self):
        reference = row("full", 10.0, 0.0, own=0.0002)
        rungs = {
            "cheap_far": row("cheap_far", 0.5, 0.004),             # on the front, within 5 % only
            "good": row("good", 2.0, 0.0008, own=0.0003),          # on the front, within both
            "cheaper_but_own_error": row("cheaper_but_own_error", 1.0, 0.0009, own=0.002),  # its own error: not within 1 %
            "dominated": row("dominated", 3.0, 0.0009),            # by "good"
            "failed": row("failed", 0.1, 0.0, outcome="diverged"),  # never on the front
        }
        with tempfile.TemporaryDirectory() as tmp:
            write_part(os.path.join(tmp, "reference"), [reference])
            for name, r in rungs.items():
                write_part(os.path.join(tmp, name), [reference, r])
            out = os.path.join(tmp, "out")
            subprocess.run([sys.executable, MERGE, out, os.path.join(tmp, "reference")] +
                           [os.path.join(tmp, n) for n in rungs], check=True)
            with open(os.path.join(out, "fidelity.json")) as f:
                merged = json.load(f)
            with open(os.path.join(out, "fidelity.csv"), newline="") as f:
                table = list(csv.DictReader(f))
        self.assertEqual([r["variant"] for r in merged["variants"]], ["full"] + list(rungs))
        front = {r["variant"] for r in merged["variants"] if r["on_front"]}
        self.assertEqual(front, {"full", "cheap_far", "good", "cheaper_but_own_error"})
        self.assertEqual({r["variant"] for r in table if r["on_front"] == "1"}, front)
        self.assertEqual(merged["cheapest_within_1_percent"]["variant"], "good")
        self.assertAlmostEqual(merged["cheapest_within_1_percent"]["speedup_over_reference"], 5.0)
        self.assertEqual(merged["cheapest_within_5_percent"]["variant"], "cheap_far")
        self.assertEqual(merged["wall_s"], 6.0)

    def test_a_missing_job_folder_is_exit_2_and_writes_nothing(self):
        with tempfile.TemporaryDirectory() as tmp:
            write_part(os.path.join(tmp, "reference"), [row("full", 1.0, 0.0)])
            out = os.path.join(tmp, "out")
            r = subprocess.run([sys.executable, MERGE, out, os.path.join(tmp, "reference"), os.path.join(tmp, "gone")],
                               capture_output=True, text=True)
            self.assertEqual(r.returncode, 2, r.stderr)
            self.assertIn("gone", r.stderr)
            self.assertFalse(os.path.exists(out))


# Held at two top corners in the wind, friction off: the yarns slide, so freezing them matters.
SCENE = """[cloth]
warps = 5
wefts = 5
[[handles]]
node = [0, 0]
[[handles]]
node = [4, 0]
[wind]
velocity_m_per_s = [0.0, 5.0, 0.0]
air_density_kg_per_m3 = 2.0
drag_Ns_per_m3 = 0.5
[terms]
friction = false
[time]
duration_s = 0.03
dt_s = 0.001
output_interval_s = 0.01
"""


class LadderAsJobs(unittest.TestCase):
    def test_jobs_and_merge_give_the_distances_of_one_run(self):
        options = ["--time-steps", "scene", "--no-error-estimate", "--quiet"]
        rungs = ["frozen_sliding", "fem_first_guess"]
        with tempfile.TemporaryDirectory() as tmp:
            scene = os.path.join(tmp, "scene.toml")
            with open(scene, "w") as f:
                f.write(SCENE)

            def fidelity(*args):
                subprocess.run([CLI, "fidelity", scene, *options, *args], check=True)

            fidelity("--variants", ",".join(rungs), "--out", os.path.join(tmp, "serial"))
            fidelity("--reference-only", "--out", os.path.join(tmp, "reference"))
            for v in rungs:
                fidelity("--variants", v, "--reference-from", os.path.join(tmp, "reference"),
                         "--out", os.path.join(tmp, v))
            subprocess.run([sys.executable, MERGE, os.path.join(tmp, "merged"), os.path.join(tmp, "reference")] +
                           [os.path.join(tmp, v) for v in rungs], check=True)
            tables = {}
            for name in ("serial", "merged"):
                with open(os.path.join(tmp, name, "fidelity.csv"), newline="") as f:
                    tables[name] = list(csv.DictReader(f))
        self.assertEqual(len(tables["merged"]), 3)
        for a, b in zip(tables["serial"], tables["merged"]):
            for column in ("variant", "dofs", "steps", "rms_m", "worst_frame_rms_m", "max_m", "energy_diff_J",
                           "compared_fraction", "outcome"):
                self.assertEqual(a[column], b[column], (a["variant"], column))
        self.assertGreater(float(tables["merged"][1]["worst_frame_rms_m"]), 1e-6)


if __name__ == "__main__":
    unittest.main()
