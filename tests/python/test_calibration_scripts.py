"""The calibration study's helper scripts (experiments/calibration/scripts/):
a scene with a [fem] table added, a parameter file with one stiffness scaled,
and the shear scan's rows, each on small files written here; bad input is exit
2 with nothing written."""
import csv
import json
import math
import os
import subprocess
import sys
import tempfile
import tomllib
import unittest

from support import SOURCE_DIR

SCRIPTS = os.path.join(SOURCE_DIR, "experiments", "calibration", "scripts")


def script(name, *args):
    return subprocess.run([sys.executable, os.path.join(SCRIPTS, name), *args], capture_output=True, text=True)


def write_run(folder, mean_time_error):
    os.makedirs(folder)
    with open(os.path.join(folder, "summary.json"), "w") as f:
        json.dump({"time_error": {"method": "richardson", "mean_rms_m": mean_time_error}}, f)


class MakeScene(unittest.TestCase):
    def test_the_keys_form_the_fem_table_after_the_scene(self):
        with tempfile.TemporaryDirectory() as tmp:
            base, out = os.path.join(tmp, "base.toml"), os.path.join(tmp, "variant", "scene.toml")
            with open(base, "w") as f:
                f.write('[cloth]\nwarps = 5\n')
            r = script("make_scene.py", base, out, "grid_line_bending=true", 'shear_law="spline"',
                       "shear_knots_rad=[0.1, 0.2]")
            self.assertEqual(r.returncode, 0, r.stderr)
            with open(out, "rb") as f:
                scene = tomllib.load(f)
        self.assertEqual(scene["cloth"], {"warps": 5})
        self.assertEqual(scene["fem"], {"grid_line_bending": True, "shear_law": "spline", "shear_knots_rad": [0.1, 0.2]})

    def test_a_scene_with_its_own_fem_table_or_a_bad_value_is_exit_2(self):
        with tempfile.TemporaryDirectory() as tmp:
            base, out = os.path.join(tmp, "base.toml"), os.path.join(tmp, "out.toml")
            with open(base, "w") as f:
                f.write('[fem]\nshear_N_per_m = 2.0\n')
            r = script("make_scene.py", base, out, "grid_line_bending=true")
            self.assertEqual(r.returncode, 2)
            self.assertIn("has a [fem] table", r.stderr)
            with open(base, "w") as f:
                f.write('[cloth]\nwarps = 5\n')
            r = script("make_scene.py", base, out, "shear_knots_rad=[0.1")
            self.assertEqual(r.returncode, 2)
            self.assertIn("shear_knots_rad=[0.1", r.stderr)
            self.assertFalse(os.path.exists(out))


class ScaleParameter(unittest.TestCase):
    def test_one_value_scaled_the_rest_kept(self):
        with tempfile.TemporaryDirectory() as tmp:
            params, out = os.path.join(tmp, "params.toml"), os.path.join(tmp, "scaled.toml")
            with open(params, "w") as f:
                f.write("# source_scene = x.toml\nshear_N_per_m = 2.1625\nwarp_bending_N_m = 1.05e-07\n")
            r = script("scale_parameter.py", params, "shear_N_per_m", "1.28", out)
            self.assertEqual(r.returncode, 0, r.stderr)
            with open(out) as f:
                lines = f.read().splitlines()
        self.assertEqual(lines[0], "# source_scene = x.toml")
        self.assertEqual(lines[1], f"shear_N_per_m = {2.1625 * 1.28!r}")
        self.assertEqual(lines[2], "warp_bending_N_m = 1.05e-07")

    def test_a_missing_key_is_exit_2(self):
        with tempfile.TemporaryDirectory() as tmp:
            params, out = os.path.join(tmp, "params.toml"), os.path.join(tmp, "scaled.toml")
            with open(params, "w") as f:
                f.write("warp_bending_N_m = 1.05e-07\n")
            r = script("scale_parameter.py", params, "shear_N_per_m", "1.28", out)
            self.assertEqual(r.returncode, 2)
            self.assertIn("shear_N_per_m", r.stderr)
            self.assertFalse(os.path.exists(out))


class ShearScan(unittest.TestCase):
    def test_rms_over_the_fitted_frames_beside_both_time_errors(self):
        with tempfile.TemporaryDirectory() as tmp:
            write_run(os.path.join(tmp, "target"), 8e-5)
            write_run(os.path.join(tmp, "scan"), 5e-5)
            distance = os.path.join(tmp, "distance.csv")
            with open(distance, "w", newline="") as f:
                w = csv.writer(f, lineterminator="\n")
                w.writerow(["time_s", "rms_distance_m", "max_distance_m", "step_time_ratio_B_over_A"])
                # t = 0 and t = 0.3 lie outside (0, 0.2]: left out
                for t, d in ((0.0, 9.0), (0.1, 3e-4), (0.2, 4e-4), (0.3, 9.0)):
                    w.writerow([t, d, 2 * d, 1.0])
            out = os.path.join(tmp, "scan.csv")
            r = script("shear_scan.py", out, os.path.join(tmp, "target"), "0.2",
                       f"1.3={os.path.join(tmp, 'scan')},{distance}")
            self.assertEqual(r.returncode, 0, r.stderr)
            with open(out, newline="") as f:
                (row,) = list(csv.DictReader(f))
        self.assertEqual(row["shear_factor"], "1.3")
        self.assertAlmostEqual(float(row["rms_over_fitted_frames_m"]), math.sqrt((9e-8 + 16e-8) / 2), delta=1e-9)
        self.assertEqual(float(row["continuum_time_error_m"]), 5e-5)
        self.assertEqual(float(row["target_time_error_m"]), 8e-5)

    def test_a_run_without_its_time_error_is_exit_2(self):
        with tempfile.TemporaryDirectory() as tmp:
            os.makedirs(os.path.join(tmp, "target"))
            with open(os.path.join(tmp, "target", "summary.json"), "w") as f:
                json.dump({}, f)
            out = os.path.join(tmp, "scan.csv")
            r = script("shear_scan.py", out, os.path.join(tmp, "target"), "0.2", f"1={tmp},{tmp}/d.csv")
            self.assertEqual(r.returncode, 2)
            self.assertIn("time_error", r.stderr)
            self.assertFalse(os.path.exists(out))


if __name__ == "__main__":
    unittest.main()
