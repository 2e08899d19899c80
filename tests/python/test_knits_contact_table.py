"""experiments/knits/scripts/contact_table.py (the knits study's contact part)
on synthetic runs: a flat 4 × 4 knit whose left edge column is lifted at the
last frame by a known angle, intersecting pairs per frame and step times. Bad
input is exit 2 with the cause named."""
import csv
import math
import os
import subprocess
import sys
import tempfile
import unittest

import numpy as np

from support import SOURCE_DIR

TABLE = os.path.join(SOURCE_DIR, "experiments", "knits", "scripts", "contact_table.py")
COURSES = WALES = 4
SCENE = f"[cloth.pattern]\nkind = \"stockinette\"\ncourses = {COURSES}\nwales = {WALES}\n"


def knit_points(lift_deg):
    """The contact nodes in the graph's order (models/knit/knit_graph.cpp), flat, with the left
    edge column (wale 0) turned up by lift_deg about the line x = 1.25 mm, the next column's mean
    x, so that its turn (the edge column against the next one) is lift_deg."""
    points, pivot, lift = [], 1.25e-3, math.radians(lift_deg)
    for r in range(-1, COURSES):
        for c in range(WALES):
            for side in range(2):
                for end in range(2):
                    x, y, z = 1e-3 * (c + 0.5 * side), 1e-3 * (r + 0.1 * end), 0.0
                    if c == 0:
                        arm = pivot - x
                        x, z = pivot - arm * math.cos(lift), arm * math.sin(lift)
                    points.append((x, y, z))
    return np.array(points)


def write_run(folder, lifts, counts, walls):
    import meshio
    os.makedirs(os.path.join(folder, "frames"))
    entries = []
    for k, lift in enumerate(lifts):
        path = os.path.join("frames", f"run_{k:05d}.vtu")
        meshio.write(os.path.join(folder, path), meshio.Mesh(knit_points(lift), [("vertex", [[0]])]))
        entries.append(f'<DataSet timestep="{0.01 * k}" group="" part="0" file="{path}"/>')
    with open(os.path.join(folder, "run.pvd"), "w") as f:
        f.write('<?xml version="1.0"?>\n<VTKFile type="Collection" version="0.1">\n<Collection>\n'
                + "\n".join(entries) + "\n</Collection>\n</VTKFile>\n")
    with open(os.path.join(folder, "self_intersections.csv"), "w") as f:
        f.write("time_s,intersecting_segment_pairs\n" + "".join(f"{0.01 * k},{c}\n" for k, c in enumerate(counts)))
    with open(os.path.join(folder, "metrics.csv"), "w") as f:
        f.write("time_s,step_wall_s\n0,0\n" + "".join(f"{0.001 * (k + 1)},{w}\n" for k, w in enumerate(walls)))


class ContactTable(unittest.TestCase):
    def test_counts_turns_and_step_ratio(self):
        with tempfile.TemporaryDirectory() as tmp:
            scene = os.path.join(tmp, "knit.toml")
            with open(scene, "w") as f:
                f.write(SCENE)
            without, with_ = os.path.join(tmp, "without"), os.path.join(tmp, "with")
            write_run(without, [0.0, 30.0, 60.0], [0, 2, 5], [0.1, 0.3, 0.2, 0.2])
            write_run(with_, [0.0, 20.0, 40.0], [0, 0, 0], [0.5, 0.4, 0.9, 0.6])
            r = subprocess.run([sys.executable, TABLE, os.path.join(tmp, "out"), f"without:{scene}:{without}",
                                f"with:{scene}:{with_}"], capture_output=True, text=True)
            self.assertEqual(r.returncode, 0, r.stderr)
            with open(os.path.join(tmp, "out", "contact.csv"), newline="") as f:
                rows = list(csv.DictReader(f))
        self.assertEqual([x["run"] for x in rows], ["without", "with"])
        first, second = rows
        self.assertEqual((first["max_intersecting_pairs"], first["frames_with_intersections"], first["frames"]),
                         ("5", "2", "3"))
        self.assertEqual((second["max_intersecting_pairs"], second["frames_with_intersections"]), ("0", "0"))
        self.assertEqual(first["steps"], "4")
        self.assertAlmostEqual(float(first["median_step_s"]), 0.2)
        self.assertAlmostEqual(float(second["median_step_s"]), 0.55)
        self.assertAlmostEqual(float(second["step_ratio"]), 2.75)
        self.assertAlmostEqual(float(first["turn_left"]), 60.0, places=3)
        self.assertAlmostEqual(float(second["turn_left"]), 40.0, places=3)
        self.assertAlmostEqual(float(first["turn_right"]), 0.0, places=6)

    def test_a_run_without_its_intersection_count_is_exit_2(self):
        with tempfile.TemporaryDirectory() as tmp:
            scene = os.path.join(tmp, "knit.toml")
            with open(scene, "w") as f:
                f.write(SCENE)
            run = os.path.join(tmp, "run")
            write_run(run, [0.0], [0], [0.1])
            os.remove(os.path.join(run, "self_intersections.csv"))
            r = subprocess.run([sys.executable, TABLE, os.path.join(tmp, "out"), f"without:{scene}:{run}"],
                               capture_output=True, text=True)
        self.assertEqual(r.returncode, 2)
        self.assertIn("self_intersections.csv: missing", r.stderr)


if __name__ == "__main__":
    unittest.main()
