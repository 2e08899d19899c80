"""A scene's [measures] (docs/models.md §3.11.6): the drape coefficient and
fold count of the last frame are the same from the command line and from
weavelab.run, and the same as experiments/cusick/scripts/drape_measure.py computes on that
frame (the definition the C++ measure follows)."""
import importlib.util
import json
import os
import subprocess
import sys
import tempfile
import unittest

import numpy as np

import weavelab
from support import CLI, SOURCE_DIR

CUSICK_33 = os.path.join(SOURCE_DIR, "experiments", "scenes", "cusick_drape_33.toml")
DRAPE_MEASURE = os.path.join(SOURCE_DIR, "experiments", "cusick", "scripts", "drape_measure.py")


def short_drape():
    """cusick_drape_33.toml over its first 30 ms, the last 10 of them settling steps: the cloth has
    reached the pedestal and its edges hang."""
    scene = weavelab.load_scene(CUSICK_33)
    scene.update({"time.duration_s": 0.03, "time.output_interval_s": 0.01, "time.settle_after_s": 0.02,
                  "time.settle_dt_s": 0.005})
    return scene


def load_drape_measure():
    sys.path.insert(0, os.path.join(SOURCE_DIR, "experiments", "common"))
    spec = importlib.util.spec_from_file_location("drape_measure", DRAPE_MEASURE)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


class Measures(unittest.TestCase):
    def test_command_line_and_python_agree(self):
        scene = short_drape()
        for model in ("yarn", "fem"):
            with tempfile.TemporaryDirectory() as tmp:
                scene_file = os.path.join(tmp, "scene.toml")
                with open(scene_file, "w") as f:
                    f.write(scene.toml)
                out = os.path.join(tmp, "cli")
                subprocess.run([CLI, "run", scene_file, "--model", model, "--quiet", "--out", out], check=True)
                with open(os.path.join(out, "summary.json")) as f:
                    cli = json.load(f)["measures"]["drape"]
            run = weavelab.run(scene, model)
            drape = run.measures["drape"]
            self.assertEqual(drape, cli, model)
            self.assertAlmostEqual(drape["time_s"], 0.03, places=12)
            self.assertLess(drape["coefficient"], 1.0)  # the edges hang below the flat cloth's outline
            self.assertGreater(drape["coefficient"], 0.0)

    def test_the_same_as_drape_measure_py_on_the_same_frame(self):
        dm = load_drape_measure()
        scene = short_drape()
        for model in ("yarn", "fem"):
            run = weavelab.run(scene, model)
            drape = run.measures["drape"]
            points = run.positions[-1]
            cells = [c for kind in ("triangle", "quad") if kind in run.cells for c in run.cells[kind]]
            lo, hi = points[:, :2].min(axis=0), points[:, :2].max(axis=0)
            mask, X, Y = dm.shadow(points, cells, lo, hi, drape["pixel_m"])
            pixel, radius = drape["pixel_m"], drape["pedestal_radius_m"]
            area = mask.sum() * pixel * pixel
            pedestal = np.pi * radius * radius
            self.assertEqual(area, drape["projected_area_m2"], model)
            self.assertEqual((area - pedestal) / (drape["cloth_area_m2"] - pedestal), drape["coefficient"], model)
            self.assertEqual(dm.folds(mask, X, Y, np.array([0.016, 0.016])), drape["folds"], model)

    def test_a_scene_without_measures_has_none(self):
        scene = short_drape()
        scene.update({"measures.drape": False})
        self.assertEqual(weavelab.run(scene, "fem").measures, {})


if __name__ == "__main__":
    unittest.main()
