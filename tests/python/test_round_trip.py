"""A run from Python gives, bit for bit, the frames of `weavelab run` on the same scene."""
import json
import os
import subprocess
import tempfile
import unittest

import numpy as np

import weavelab
from support import CLI, read_vtu, small_scene


class RoundTrip(unittest.TestCase):
    def compare(self, model):
        scene = small_scene(weavelab)
        with tempfile.TemporaryDirectory() as tmp:
            scene_file = os.path.join(tmp, "scene.toml")
            with open(scene_file, "w") as f:
                f.write(scene.toml)
            cli_out = os.path.join(tmp, "cli")
            subprocess.run([CLI, "run", scene_file, "--model", model, "--quiet", "--out", cli_out], check=True)
            run = weavelab.run(scene, model)
            self.assertEqual(run.outcome, "ok")
            frames = sorted(os.listdir(os.path.join(cli_out, "frames")))
            self.assertEqual(len(frames), len(run.times))
            self.assertEqual(len(frames), 5)  # t = 0, 0.005, …, 0.02
            for k, name in enumerate(frames):
                vtu = read_vtu(os.path.join(cli_out, "frames", name))
                # Bitwise: equal as numbers and in sign (array_equal alone takes 0.0 == -0.0).
                self.assertTrue(np.array_equal(vtu["positions"], run.positions[k]), name)
                self.assertTrue(np.array_equal(np.signbit(vtu["positions"]), np.signbit(run.positions[k])))
                self.assertTrue(np.array_equal(vtu["velocity"], run.velocities[k]), name)
                for key in ("u", "v"):
                    if key in vtu:
                        self.assertTrue(np.array_equal(vtu[key], run.point_data[key][k]), (name, key))
            # The cloth moved: the frames are not the initial state repeated.
            self.assertGreater(np.abs(run.positions[-1] - run.positions[0]).max(), 1e-6)
            with open(os.path.join(cli_out, "summary.json")) as f:
                cli_summary = json.load(f)
            self.assertEqual(cli_summary["statistics"]["steps"], run.summary["statistics"]["steps"])

    def test_yarn(self):
        self.compare("yarn")

    def test_fem(self):
        self.compare("fem")

    def test_sliding_coordinates_move(self):
        run = weavelab.run(small_scene(weavelab))
        self.assertEqual(run.u.shape, run.positions.shape[:2])
        self.assertGreater(np.abs(run.u[-1] - run.u[0]).max(), 0.0)

    def test_written_folder_matches_memory(self):
        scene = small_scene(weavelab, duration=0.01)
        with tempfile.TemporaryDirectory() as tmp:
            run = weavelab.run(scene, out=os.path.join(tmp, "run"))
            last = sorted(os.listdir(os.path.join(tmp, "run", "frames")))[-1]
            self.assertTrue(np.array_equal(read_vtu(os.path.join(tmp, "run", "frames", last))["positions"],
                                           run.positions[-1]))
            with open(os.path.join(tmp, "run", "summary.json")) as f:
                self.assertEqual(json.load(f)["result"], run.summary["result"])


if __name__ == "__main__":
    unittest.main()
