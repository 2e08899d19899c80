"""Scripts of the cusick and knits studies on synthetic inputs:
experiments/cusick/scripts/contact_cost.py (per-step means and medians of a
drape and its free fall, and their ratios, from summary.json and metrics.csv)
and experiments/knits/scripts/woven_scene.py (the woven partner of the knit
pull: n × n crossings whose yarn length per area 2n / ((n − 1) L) is the
knit's). Bad input is exit 2 with the cause named."""
import csv
import json
import os
import subprocess
import sys
import tempfile
import tomllib
import unittest

from support import SOURCE_DIR

COST = os.path.join(SOURCE_DIR, "experiments", "cusick", "scripts", "contact_cost.py")
WOVEN = os.path.join(SOURCE_DIR, "experiments", "knits", "scripts", "woven_scene.py")
KNIT = os.path.join(SOURCE_DIR, "experiments", "scenes", "knit_stockinette.toml")


def write_run(folder, steps_wall, wall_s, cpu_s, factorizations, krylov):
    """A run folder with metrics.csv (the initial row, then one row per step) and summary.json."""
    os.makedirs(folder)
    with open(os.path.join(folder, "metrics.csv"), "w") as f:
        f.write("time_s,step_wall_s\n0,0\n" + "".join(f"{0.001 * (k + 1)},{w}\n" for k, w in enumerate(steps_wall)))
    with open(os.path.join(folder, "summary.json"), "w") as f:
        json.dump({"statistics": {"steps": len(steps_wall), "wall_s": wall_s, "cpu_s": cpu_s,
                                  "factorizations": factorizations, "krylov_iters": krylov,
                                  "linear_solver": "gmres (restart 40)"}}, f)


class ContactCost(unittest.TestCase):
    def test_means_medians_and_ratios(self):
        with tempfile.TemporaryDirectory() as tmp:
            drape, free, out = (os.path.join(tmp, n) for n in ("drape", "free", "cost.csv"))
            write_run(free, [0.1, 0.3, 0.2, 0.2], wall_s=0.8, cpu_s=0.4, factorizations=1, krylov=2)
            write_run(drape, [0.5, 0.4, 0.9, 0.6], wall_s=2.4, cpu_s=1.6, factorizations=3, krylov=40)
            r = subprocess.run([sys.executable, COST, "--runs", f"s33:yarn:{drape}:{free}", "--out", out],
                               capture_output=True, text=True)
            self.assertEqual(r.returncode, 0, r.stderr)
            with open(out, newline="") as f:
                rows = list(csv.DictReader(f))
        self.assertEqual([(x["scene"], x["model"], x["run"]) for x in rows], [("s33", "yarn", "free"),
                                                                             ("s33", "yarn", "drape")])
        free_row, drape_row = rows
        self.assertAlmostEqual(float(free_row["mean_wall_per_step_ms"]), 200.0)
        self.assertAlmostEqual(float(free_row["mean_cpu_per_step_ms"]), 100.0)
        self.assertAlmostEqual(float(free_row["median_step_wall_ms"]), 200.0)
        self.assertAlmostEqual(float(drape_row["median_step_wall_ms"]), 550.0)
        self.assertAlmostEqual(float(drape_row["ratio_mean_wall"]), 3.0)
        self.assertAlmostEqual(float(drape_row["ratio_mean_cpu"]), 4.0)
        self.assertAlmostEqual(float(drape_row["ratio_median_wall"]), 2.75)
        self.assertEqual((drape_row["factorizations"], drape_row["gmres_iterations"], drape_row["linear_solver"]),
                         ("3", "40", "gmres"))

    def test_a_run_without_statistics_is_exit_2(self):
        with tempfile.TemporaryDirectory() as tmp:
            drape, free = os.path.join(tmp, "drape"), os.path.join(tmp, "free")
            write_run(drape, [0.5], wall_s=0.5, cpu_s=0.5, factorizations=1, krylov=0)
            os.makedirs(free)
            with open(os.path.join(free, "summary.json"), "w") as f:
                json.dump({}, f)
            r = subprocess.run([sys.executable, COST, "--runs", f"s:yarn:{drape}:{free}", "--out",
                                os.path.join(tmp, "cost.csv")], capture_output=True, text=True)
            self.assertEqual(r.returncode, 2)
            self.assertIn("no statistics", r.stderr)
            self.assertFalse(os.path.exists(os.path.join(tmp, "cost.csv")))


class WovenScene(unittest.TestCase):
    def woven(self, pull):
        tmp = tempfile.TemporaryDirectory()
        self.addCleanup(tmp.cleanup)
        pull_path, out = os.path.join(tmp.name, "pull.json"), os.path.join(tmp.name, "woven.toml")
        with open(pull_path, "w") as f:
            json.dump(pull, f)
        r = subprocess.run([sys.executable, WOVEN, KNIT, pull_path, out], capture_output=True, text=True)
        if not os.path.exists(out):
            return r, None
        with open(out, "rb") as f:
            return r, tomllib.load(f)

    def test_same_yarn_length_per_area_and_yarn(self):
        rho, size = 2242.2, 0.0128
        r, scene = self.woven({"yarn_length_per_area_per_m": rho, "grip_distance_m": size})
        self.assertEqual(r.returncode, 0, r.stderr)
        with open(KNIT, "rb") as f:
            knit = tomllib.load(f)
        n, spacing = scene["cloth"]["warps"], scene["cloth"]["spacing_m"]
        self.assertEqual(n, round(size * rho / 2) + 1)
        self.assertEqual(scene["cloth"]["wefts"], n)
        self.assertAlmostEqual(2 * n / ((n - 1) * spacing), rho, delta=1e-9 * rho)
        self.assertEqual(scene["cloth"]["radius_m"], knit["cloth"]["radius_m"])
        for key in ("density_kg_per_m", "stretch_modulus_Pa", "bending_modulus_Pa"):
            self.assertEqual(scene["yarn_types"]["default"][key], knit["yarn_types"]["default"][key])
        self.assertEqual(scene["gravity"]["acceleration_m_per_s2"], [0.0, 0.0, 0.0])

    def test_at_least_five_crossings(self):
        r, scene = self.woven({"yarn_length_per_area_per_m": 100.0, "grip_distance_m": 0.01})
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertEqual(scene["cloth"]["warps"], 5)

    def test_a_pull_without_its_keys_is_exit_2(self):
        r, scene = self.woven({"grip_distance_m": 0.01})
        self.assertEqual(r.returncode, 2)
        self.assertIn("yarn_length_per_area_per_m", r.stderr)
        self.assertIsNone(scene)


if __name__ == "__main__":
    unittest.main()
