"""The frame-by-frame table of the slide-pull study
(experiments/slide_pull/scripts/slide_pull_table.py) on two synthetic runs: the RMS and largest
distance per frame beside each run's time error and slide indicator; a run
without a time error estimate is exit 2."""
import json
import os
import subprocess
import sys
import tempfile
import unittest

import meshio
import numpy as np

from support import SOURCE_DIR

SCRIPT = os.path.join(SOURCE_DIR, "experiments", "slide_pull", "scripts", "slide_pull_table.py")
POINTS = np.array([[0.0, 0, 0], [1e-3, 0, 0], [0, 1e-3, 0], [1e-3, 1e-3, 0]])


def write_run(folder, shift, sliding, time_error=None):
    """Two frames (t = 0 and 5 ms); at 5 ms every point moved by `shift` [m]."""
    os.makedirs(folder)
    entries = []
    for k, t in enumerate((0.0, 0.005)):
        points = POINTS + (np.array(shift) if k else 0.0)
        slide = np.array([0.0, 0.0, sliding, 0.2, 0.0, 0.0, 0.0, 0.0]) if k else np.zeros(8)
        name = f"run_{k:05d}.vtu"
        meshio.write(os.path.join(folder, name), meshio.Mesh(points, [("vertex", np.arange(4).reshape(-1, 1))],
                                                             point_data={"sliding": slide.reshape(4, 2)}))
        entries.append(f'<DataSet timestep="{t}" file="{name}"/>')
    with open(os.path.join(folder, "run.pvd"), "w") as f:
        f.write('<VTKFile type="Collection"><Collection>' + "".join(entries) + "</Collection></VTKFile>")
    summary = {} if time_error is None else {
        "time_error": {"times_s": [0.005], "rms_m": [time_error], "mean_rms_m": time_error}}
    with open(os.path.join(folder, "summary.json"), "w") as f:
        json.dump(summary, f)


class SlidePullTable(unittest.TestCase):
    def test_distance_beside_time_errors_and_slide_indicator(self):
        with tempfile.TemporaryDirectory() as tmp:
            a, b = os.path.join(tmp, "a"), os.path.join(tmp, "b")
            write_run(a, [0, 0, 0], 0.9, 2e-6)
            write_run(b, [3e-5, 4e-5, 0], 0.1, 5e-6)  # every point 50 μm from run a at 5 ms
            r = subprocess.run([sys.executable, SCRIPT, a, b], capture_output=True, text=True)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertIn("| 5 | 50 / 50 | 2 / 5 | 0.9, 1 | 0.2, 0 |", r.stdout)
        self.assertIn("| 0 | 0 / 0 | – / – | 0, 0 | 0, 0 |", r.stdout)
        self.assertIn("RMS distance: 50 μm; mean time error: A 2 μm, B 5 μm", r.stdout)

    def test_a_run_without_time_error_is_exit_2(self):
        with tempfile.TemporaryDirectory() as tmp:
            a, b = os.path.join(tmp, "a"), os.path.join(tmp, "b")
            write_run(a, [0, 0, 0], 0.9, 2e-6)
            write_run(b, [0, 0, 0], 0.9)
            r = subprocess.run([sys.executable, SCRIPT, a, b], capture_output=True, text=True)
        self.assertEqual(r.returncode, 2)
        self.assertIn("--error-estimate", r.stderr)


if __name__ == "__main__":
    unittest.main()
