"""calibrate and fit from Python: the drivers of `weavelab calibrate` and
`weavelab fit`, their results as dicts."""
import os
import tempfile
import unittest

import weavelab
from support import HANGING_WIND, small_scene


class Studies(unittest.TestCase):
    def test_calibrate_returns_its_json(self):
        scene = weavelab.load_scene(HANGING_WIND)
        with tempfile.TemporaryDirectory() as tmp:
            out = os.path.join(tmp, "cal")
            result = weavelab.calibrate(scene, out, tests=["shear"], free=["shear_N_per_m"], patch=7, starts=1)
            self.assertTrue(result["converged"])
            self.assertEqual(result["out"], out)
            self.assertTrue(os.path.isfile(os.path.join(out, "params.toml")))
            shear = next(p for p in result["parameters"] if p["key"] == "shear_N_per_m")
            self.assertGreater(shear["value"], 0.0)
            self.assertNotEqual(shear["value"], shear["start"])
            self.assertFalse(shear["at_bound"])

    def test_fit_recovers_a_scene_key(self):
        truth = small_scene(weavelab, size=5)
        with tempfile.TemporaryDirectory() as tmp:
            weavelab.run(truth, out=os.path.join(tmp, "target"))
            start = truth.copy()
            start["contact.shear_modulus_Pa"] = 1500.0  # the truth is 1000 Pa
            result = weavelab.fit(start, os.path.join(tmp, "target"), ["contact.shear_modulus_Pa"],
                                  os.path.join(tmp, "fit"), max_iterations=10)
            self.assertTrue(result["converged"])
            (p,) = result["parameters"]
            self.assertEqual(p["start"], 1500.0)
            self.assertAlmostEqual(p["value"], 1000.0, delta=1.0)

    def test_bad_input_before_anything_runs(self):
        with tempfile.TemporaryDirectory() as tmp:
            with self.assertRaises(ValueError) as e:
                weavelab.calibrate(HANGING_WIND, os.path.join(tmp, "cal"), tests=["no_such_test"])
            self.assertIn("no_such_test", str(e.exception))
            self.assertFalse(os.path.exists(os.path.join(tmp, "cal", "calibration.json")))

    def test_time_steps_and_its_old_keyword(self):
        with tempfile.TemporaryDirectory() as tmp:
            with self.assertRaises(ValueError) as e:
                weavelab.calibrate(HANGING_WIND, os.path.join(tmp, "cal"), time_steps="fine")
            self.assertIn("time_steps: got 'fine'", str(e.exception))
            # resolution=, the old name, still works and warns
            with self.assertWarns(DeprecationWarning), self.assertRaises(ValueError) as e:
                weavelab.calibrate(HANGING_WIND, os.path.join(tmp, "cal"), resolution="fine")
            self.assertIn("got 'fine'", str(e.exception))
            self.assertFalse(os.path.exists(os.path.join(tmp, "cal")))


if __name__ == "__main__":
    unittest.main()
