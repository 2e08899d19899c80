"""The validation table of the calibration study
(experiments/calibration/scripts/validation_table.py) on synthetic runs: each distance beside both
runs' time errors with the verdict their sizes give, the Markdown table and the
chart written; a missing distance file is exit 2."""
import csv
import json
import os
import subprocess
import sys
import tempfile
import unittest

from support import SOURCE_DIR

SCRIPT = os.path.join(SOURCE_DIR, "experiments", "calibration", "scripts", "validation_table.py")
KINDS = ["first_guess", "static", "dynamic", "yarnmass", "shear_scaled", "spline", "spline_mass"]


def write_run(folder, mean_time_error):
    os.makedirs(folder)
    with open(os.path.join(folder, "summary.json"), "w") as f:
        json.dump({"time_error": {"method": "richardson", "mean_rms_m": mean_time_error, "max_m": 2 * mean_time_error}},
                  f)


def write_distance(path, rms):
    with open(path, "w", newline="") as f:
        w = csv.writer(f, lineterminator="\n")
        w.writerow(["time_s", "rms_distance_m", "max_distance_m", "step_time_ratio_B_over_A"])
        w.writerow([0.0, 0.0, 0.0, 1.0])  # t = 0 is left out of the mean
        for k, d in enumerate(rms):
            w.writerow([0.01 * (k + 1), d, 2 * d, 1.0])


class ValidationTable(unittest.TestCase):
    def test_distances_stand_beside_both_time_errors(self):
        with tempfile.TemporaryDirectory() as tmp:
            write_run(os.path.join(tmp, "yarn_a"), 1e-5)
            for i, kind in enumerate(KINDS):
                # continuum time errors: 1e-5 (resolved), 5e-4 (above a tenth), 3e-3 (exceeds) ...
                write_run(os.path.join(tmp, f"fem_{kind}_a"), [1e-5, 5e-4, 3e-3, 1e-5, 1e-5, 1e-5, 1e-5][i])
                write_distance(os.path.join(tmp, f"distance_{kind}_a.csv"), [1e-3, 3e-3])
            r = subprocess.run([sys.executable, SCRIPT, tmp, "a=" + os.path.join(tmp, "yarn_a")],
                               capture_output=True, text=True)
            self.assertEqual(r.returncode, 0, r.stderr)
            with open(os.path.join(tmp, "summary.csv"), newline="") as f:
                rows = list(csv.DictReader(f))
            self.assertTrue(os.path.isfile(os.path.join(tmp, "validation.png")))
            with open(os.path.join(tmp, "summary.md")) as f:
                table = f.read()
        self.assertEqual([row["continuum"] for row in rows], KINDS)
        self.assertAlmostEqual(float(rows[0]["mean_rms_m"]), 2e-3)  # mean over the frames after t = 0
        self.assertAlmostEqual(float(rows[0]["worst_frame_rms_m"]), 3e-3)
        self.assertAlmostEqual(float(rows[0]["max_m"]), 6e-3)
        self.assertEqual([row["verdict"] for row in rows[:3]],
                         ["resolved", "time error above a tenth of the distance", "time error exceeds the distance"])
        self.assertIn("| `a` | 2.00 mm |", table)

    def test_a_missing_distance_file_is_exit_2(self):
        with tempfile.TemporaryDirectory() as tmp:
            write_run(os.path.join(tmp, "yarn_a"), 1e-5)
            r = subprocess.run([sys.executable, SCRIPT, tmp, "a=" + os.path.join(tmp, "yarn_a")],
                               capture_output=True, text=True)
            self.assertEqual(r.returncode, 2)
            self.assertIn("distance_first_guess_a.csv", r.stderr)
            self.assertFalse(os.path.exists(os.path.join(tmp, "summary.csv")))


if __name__ == "__main__":
    unittest.main()
