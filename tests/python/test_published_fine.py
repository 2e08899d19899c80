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


def write_lab(folder, step, error_rms):
    """A weavelab run folder: a frame every `step` over STEPS·H, the time error per frame in its summary."""
    import meshio
    os.makedirs(os.path.join(folder, "frames"))
    entries = []
    count = round(STEPS * H / step)
    for k in range(count + 1):
        t = k * step
        path = os.path.join("frames", f"run_{k:05d}.vtu")
        points = exact(t) + np.array([0.0, DRIFT * t, 0.0])
        meshio.write(os.path.join(folder, path), meshio.Mesh(points, [("vertex", [[0]])]))
        entries.append(f'<DataSet timestep="{t!r}" group="" part="0" file="{path}"/>')
    with open(os.path.join(folder, "run.pvd"), "w") as f:
        f.write('<?xml version="1.0"?>\n<VTKFile type="Collection" version="0.1">\n<Collection>\n'
                + "\n".join(entries) + "\n</Collection>\n</VTKFile>\n")
    times = [k * step for k in range(count + 1)]
    with open(os.path.join(folder, "summary.json"), "w") as f:
        json.dump({"time_error": {"times_s": times, "rms_m": [error_rms * t / H for t in times]}}, f)


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


def write_levels(tmp, covered=STEPS * H):
    """Published and lab runs at H, 2H and 4H; the published run at 4H stops at `covered`."""
    lab_error = 1e-7
    for n, level in enumerate(("h", "2h", "4h")):
        step = H * 2 ** n
        write_published(os.path.join(tmp, f"pub_{level}"), step, STEPS * H if level != "4h" else covered)
        write_lab(os.path.join(tmp, f"lab_{level}"), step, lab_error)
    return lab_error


def compare(tmp):
    out = os.path.join(tmp, "fine.csv")
    done = run_script("compare_fine.py", "--step-s", repr(H),
                      "--published", f"direct={tmp}/pub_h,{tmp}/pub_2h,{tmp}/pub_4h",
                      "--run", f"compat={tmp}/lab_h,{tmp}/lab_2h,{tmp}/lab_4h", "--out", out)
    rows = []
    if os.path.exists(out):
        with open(out, newline="") as f:
            rows = list(csv.DictReader(f))
    return done, rows


class CompareFine(unittest.TestCase):
    def test_distances_and_time_errors_in_closed_form(self):
        with tempfile.TemporaryDirectory() as tmp:
            lab_error = write_levels(tmp)
            done, rows = compare(tmp)
            self.assertEqual(done.returncode, 0, done.stderr)
            self.assertEqual([r["level"] for r in rows], ["H", "2H", "4H", "zero step"])
            t = STEPS * H  # every quantity below grows with t: its worst is at the last step
            motion = math.hypot(SLOPE * H * t, FALL * t * t)
            for row, step in zip(rows, (H, 2 * H, 4 * H)):
                # The published run at S is SLOPE·S·t from the exact motion, and its estimate from the
                # neighbouring run (first order) is exactly that; the lab run is DRIFT·t from the exact
                # motion along another axis.
                self.assertEqual(float(row["step_s"]), step)
                self.assertAlmostEqual(float(row["largest_rms_motion_m"]) / motion, 1.0, places=12)
                self.assertAlmostEqual(float(row["fraction_of_motion"]),
                                       math.hypot(SLOPE * step * t, DRIFT * t) / motion, places=12)
                self.assertAlmostEqual(float(row["against_time_error_worst_fraction"]), SLOPE * step * t / motion,
                                       places=12)
                self.assertAlmostEqual(float(row["run_time_error_worst_fraction"]), lab_error * t / H / motion,
                                       places=12)
                self.assertEqual(float(row["against_worst_solve_residual"]), 3e-15)
                self.assertEqual((row["run"], row["against"]), ("compat", "published (direct)"))
            # Extrapolated to a zero step the published step's error is gone and the models' difference,
            # DRIFT·t, is left; the extrapolation is exact here, so its error estimate is zero.
            zero = rows[3]
            self.assertAlmostEqual(float(zero["fraction_of_motion"]), DRIFT * t / motion, places=12)
            self.assertLess(float(zero["run_time_error_worst_fraction"]), 1e-12)

    def test_coarse_run_that_does_not_cover_is_exit_2(self):
        with tempfile.TemporaryDirectory() as tmp:
            write_levels(tmp, covered=2 * H)  # the run at 4H stops halfway
            done, rows = compare(tmp)
            self.assertEqual(done.returncode, 2)
            self.assertIn("does not cover", done.stderr)
            self.assertEqual(rows, [])


if __name__ == "__main__":
    unittest.main()
