"""The published_code study's fine-step comparison (experiments/published_code/scripts):
make_variant.py's time keys, and compare_fine.py on synthetic runs whose distances and time errors
are known in closed form. Bad input is exit 2 with the cause named."""
import csv
import json
import math
import os
import subprocess
import sys
import tempfile
import unittest

import numpy as np

from support import SOURCE_DIR

SCRIPTS = os.path.join(SOURCE_DIR, "experiments", "published_code", "scripts")
SCENE = os.path.join(SOURCE_DIR, "experiments", "published_code", "scenes", "authors_homogeneous_17.toml")
NU, NV = 3, 2            # nodes per row, rows
H = 1e-3                 # the fine step
STEPS = 4                # steps at H
FALL = 2.0               # z = −FALL·t² [m]: the motion
SLOPE = 0.3              # the published step's first-order error: x += SLOPE·step·t
DRIFT = 0.05             # the lab run's distance from the exact motion: y += DRIFT·t


def run_script(name, *args):
    return subprocess.run([sys.executable, os.path.join(SCRIPTS, name), *args], capture_output=True, text=True)


def exact(t):
    """(NU·NV, 3) positions, node i + NU·j, at time t."""
    grid = np.array([(1e-3 * i, 0.0, -1e-3 * j) for j in range(NV) for i in range(NU)])
    return grid + np.array([0.0, 0.0, -FALL * t * t])


def write_published(folder, step, duration=STEPS * H):
    """The driver's trajectory.csv and solver.csv of a first-order run at `step` over `duration`."""
    os.makedirs(folder)
    with open(os.path.join(folder, "trajectory.csv"), "w") as f:
        f.write("step,time_s,i,j,x,y,z,u,v,vx,vy,vz,udot,vdot,u_anchor,v_anchor\n")
        for k in range(round(duration / step) + 1):
            t = k * step
            x = exact(t) + np.array([SLOPE * step * t, 0.0, 0.0])
            for n, p in enumerate(x):
                f.write(f"{k},{t!r},{n % NU},{n // NU},{p[0]!r},{p[1]!r},{p[2]!r},,,0,0,0,,,,\n")
    with open(os.path.join(folder, "solver.csv"), "w") as f:
        f.write("step,relative_residual\n0,1e-15\n1,3e-15\n")


def write_lab(folder, error_rms):
    """A weavelab run folder: a frame every step H, the time error per frame in its summary."""
    import meshio
    os.makedirs(os.path.join(folder, "frames"))
    entries = []
    for k in range(STEPS + 1):
        t = k * H
        path = os.path.join("frames", f"run_{k:05d}.vtu")
        points = exact(t) + np.array([0.0, DRIFT * t, 0.0])
        meshio.write(os.path.join(folder, path), meshio.Mesh(points, [("vertex", [[0]])]))
        entries.append(f'<DataSet timestep="{t!r}" group="" part="0" file="{path}"/>')
    with open(os.path.join(folder, "run.pvd"), "w") as f:
        f.write('<?xml version="1.0"?>\n<VTKFile type="Collection" version="0.1">\n<Collection>\n'
                + "\n".join(entries) + "\n</Collection>\n</VTKFile>\n")
    times = [k * H for k in range(STEPS + 1)]
    with open(os.path.join(folder, "summary.json"), "w") as f:
        json.dump({"time_error": {"times_s": times, "rms_m": [error_rms * k for k in range(STEPS + 1)]}}, f)


class MakeVariantTime(unittest.TestCase):
    def test_time_keys_replaced_and_compat_appended(self):
        with tempfile.TemporaryDirectory() as tmp:
            out = os.path.join(tmp, "v.toml")
            done = run_script("make_variant.py", SCENE, out, "--dt-s", "0.00025", "--duration-s", "0.01",
                              'ring_over_under = "none"')
            self.assertEqual(done.returncode, 0, done.stderr)
            with open(out) as f:
                lines = f.read().splitlines()
            self.assertIn("duration_s = 0.01", lines)
            self.assertIn("dt_s = 0.00025", lines)
            self.assertIn("output_interval_s = 0.00025", lines)
            self.assertEqual(lines[-2:], ["[compat]   # docs/published_code.md", 'ring_over_under = "none"'])
            with open(SCENE) as f:
                base = f.read().splitlines()
            changed = [line for line in base if line not in lines]
            self.assertEqual(len(changed), 3, changed)  # only the three time keys

    def test_bad_time_is_exit_2_named(self):
        with tempfile.TemporaryDirectory() as tmp:
            out = os.path.join(tmp, "v.toml")
            done = run_script("make_variant.py", SCENE, out, "--dt-s", "0.0003", "--duration-s", "0.01")
            self.assertEqual(done.returncode, 2)
            self.assertIn("--dt-s 0.0003", done.stderr)
            self.assertIn("divides", done.stderr)
            done = run_script("make_variant.py", SCENE, out, "--dt-s", "0.00025")
            self.assertEqual(done.returncode, 2)
            self.assertIn("go together", done.stderr)
            self.assertFalse(os.path.exists(out))


class CompareFine(unittest.TestCase):
    def test_distances_and_time_errors_in_closed_form(self):
        with tempfile.TemporaryDirectory() as tmp:
            write_published(os.path.join(tmp, "pub_h"), H)
            write_published(os.path.join(tmp, "pub_2h"), 2 * H)
            lab_error = 1e-7
            write_lab(os.path.join(tmp, "lab"), lab_error)
            out = os.path.join(tmp, "fine.csv")
            done = run_script("compare_fine.py", "--step-s", repr(H),
                              "--published", f"direct={tmp}/pub_h,{tmp}/pub_2h", "--run", f"compat={tmp}/lab",
                              "--out", out)
            self.assertEqual(done.returncode, 0, done.stderr)
            with open(out, newline="") as f:
                rows = list(csv.DictReader(f))
            self.assertEqual(len(rows), 1)
            row = rows[0]
            t = STEPS * H  # every quantity below grows with t: its worst is at the last step
            motion = math.hypot(SLOPE * H * t, FALL * t * t)
            # The published run at H is SLOPE·H·t from the exact motion, its estimate from the run at 2H
            # (first order) is exactly that; the lab run's distance from it is √((SLOPE·H·t)² + (DRIFT·t)²).
            self.assertAlmostEqual(float(row["largest_rms_motion_m"]) / motion, 1.0, places=12)
            self.assertAlmostEqual(float(row["fraction_of_motion"]),
                                   math.hypot(SLOPE * H * t, DRIFT * t) / motion, places=12)
            self.assertAlmostEqual(float(row["against_time_error_worst_fraction"]), SLOPE * H * t / motion,
                                   places=12)
            self.assertAlmostEqual(float(row["run_time_error_worst_fraction"]), lab_error * STEPS / motion,
                                   places=12)
            self.assertEqual(float(row["against_worst_solve_residual"]), 3e-15)
            self.assertEqual(row["run"], "compat")
            self.assertEqual(row["against"], "published (direct)")

    def test_coarse_run_that_does_not_cover_is_exit_2(self):
        with tempfile.TemporaryDirectory() as tmp:
            write_published(os.path.join(tmp, "pub_h"), H)
            write_published(os.path.join(tmp, "pub_2h"), 2 * H, duration=2 * H)  # stops halfway
            write_lab(os.path.join(tmp, "lab"), 1e-7)
            done = run_script("compare_fine.py", "--step-s", repr(H),
                              "--published", f"direct={tmp}/pub_h,{tmp}/pub_2h", "--run", f"compat={tmp}/lab",
                              "--out", os.path.join(tmp, "fine.csv"))
            self.assertEqual(done.returncode, 2)
            self.assertIn("does not cover", done.stderr)
            self.assertFalse(os.path.exists(os.path.join(tmp, "fine.csv")))


if __name__ == "__main__":
    unittest.main()
