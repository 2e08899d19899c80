"""The diagnosis study's tables (experiments/diagnosis/scripts/diagnosis_tables.py)
on small synthetic folders: the budget from diagnosis.json, the warp/weft
energy changes averaged over a window of frames, each yarn mode beside its
partners, the equilibria; a missing file is exit 2 with nothing written."""
import csv
import json
import os
import subprocess
import sys
import tempfile
import unittest

from support import SOURCE_DIR

SCRIPT = os.path.join(SOURCE_DIR, "experiments", "diagnosis", "scripts", "diagnosis_tables.py")


def write_csv(path, head, rows):
    with open(path, "w", newline="") as f:
        w = csv.writer(f, lineterminator="\n")
        w.writerow(head)
        w.writerows(rows)


def write_diagnose(folder):
    os.makedirs(folder)
    with open(os.path.join(folder, "diagnosis.json"), "w") as f:
        json.dump({"scene": {"file": "experiments/scenes/x.toml"}, "resolution": "sdirk2",
                   "distance_mean_rms_m": 1e-3, "border_rms_m": 2e-3, "interior_rms_m": 5e-4, "verdict": "resolved",
                   "yarn_time_error": {"mean_rms_m": 8e-5}, "fem_time_error": {"mean_rms_m": 3e-5}}, f)
    rows = []
    for t, e in ((0.0, 1.0), (0.1, 2.0), (0.2, 4.0), (0.3, 100.0)):  # t = 0.3 lies outside the window [0.1, 0.2]
        for model in ("yarn", "fem"):
            rows.append([t, model, "stretch", e, 2 * e])
            rows.append([t, model, "bending", 3 * e, e])
    rows.append([0.1, "fem", "fem-border-stretch", 1.0, 0.0])  # a second stretch term adds to the first at its time
    write_csv(os.path.join(folder, "energy_directions.csv"), ["time_s", "model", "term", "warp_J", "weft_J"], rows)


def write_modes(folder, partner_hz):
    os.makedirs(folder)
    write_csv(os.path.join(folder, "modes.csv"),
              ["model", "mode", "frequency_hz", "eigenvalue_per_s2", "paired_mode", "paired_frequency_hz", "mac",
               "frequency_ratio_fem_to_yarn"],
              [["yarn", 0, 4.0, 1, 1, partner_hz, 0.9, 1], ["yarn", 1, 6.0, 1, 0, 5.0, 0.05, 1],
               ["fem", 0, 5.0, 1, 1, 6.0, 0.05, 1]])
    model = {"equilibrium": "Newton", "equilibrium_newton_iterations": 3, "equilibrium_residual_N": 1e-14,
             "planar_hang_lowest_hz": -15.0, "stable": True, "stiffness_asymmetry": 1e-18}
    with open(os.path.join(folder, "modes.json"), "w") as f:
        json.dump({"yarn": model, "fem": model, "equilibria_rms_distance_m": 2e-4}, f)


class DiagnosisTables(unittest.TestCase):
    def run_script(self, tmp, count="1"):
        return subprocess.run([sys.executable, SCRIPT, os.path.join(tmp, "tables"), os.path.join(tmp, "diagnose"),
                               "0.1", "0.2", count, f"first_guess={tmp}/fg", f"calibrated={tmp}/cal"],
                              capture_output=True, text=True)

    def test_tables(self):
        with tempfile.TemporaryDirectory() as tmp:
            write_diagnose(os.path.join(tmp, "diagnose"))
            write_modes(os.path.join(tmp, "fg"), 4.5)
            write_modes(os.path.join(tmp, "cal"), 4.1)
            r = self.run_script(tmp)
            self.assertEqual(r.returncode, 0, r.stderr)
            def read(name):
                with open(os.path.join(tmp, "tables", name), newline="") as f:
                    return list(csv.DictReader(f))
            budget, directions, modes = read("budget.csv"), read("directions.csv"), read("modes.csv")
            equilibria = read("equilibria.csv")
        self.assertEqual(budget[0]["scene"], "x.toml")
        self.assertEqual(float(budget[0]["yarn_time_error_m"]), 8e-5)
        self.assertEqual(float(budget[0]["continuum_time_error_m"]), 3e-5)
        by = {row["energy"]: row for row in directions}
        # yarn stretch warp: changes since t = 0 at 0.1 and 0.2 are 1 and 3: mean 2
        self.assertAlmostEqual(float(by["stretch"]["yarn_warp_J"]), 2.0)
        self.assertAlmostEqual(float(by["stretch"]["yarn_weft_J"]), 4.0)
        self.assertAlmostEqual(float(by["bending"]["yarn_warp_J"]), 6.0)
        # fem stretch warp: the border term adds 1 at 0.1: changes 2 and 3, mean 2.5
        self.assertAlmostEqual(float(by["stretch"]["fem_warp_J"]), 2.5)
        self.assertEqual(len(modes), 1)  # MODES_ROWS = 1
        self.assertEqual(float(modes[0]["first_guess_partner_hz"]), 4.5)
        self.assertEqual(float(modes[0]["calibrated_partner_hz"]), 4.1)
        self.assertEqual([(row["continuum"], row["model"]) for row in equilibria],
                         [("first_guess", "yarn"), ("first_guess", "fem"), ("calibrated", "yarn"), ("calibrated", "fem")])

    def test_a_missing_modes_folder_is_exit_2(self):
        with tempfile.TemporaryDirectory() as tmp:
            write_diagnose(os.path.join(tmp, "diagnose"))
            write_modes(os.path.join(tmp, "fg"), 4.5)
            r = self.run_script(tmp)
            self.assertEqual(r.returncode, 2)
            self.assertIn(os.path.join(tmp, "cal", "modes.csv"), r.stderr)
            self.assertFalse(os.path.exists(os.path.join(tmp, "tables")))


if __name__ == "__main__":
    unittest.main()
