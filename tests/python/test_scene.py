"""Scenes from Python: edits checked by the scene parser, errors that name the key,
and the forgiving duration rule of `weavelab run`."""
import os
import subprocess
import sys
import tempfile
import unittest

import weavelab
from support import HANGING_WIND, small_scene


class SceneEdits(unittest.TestCase):
    def test_load_and_read(self):
        scene = weavelab.load_scene(HANGING_WIND)
        self.assertEqual(scene["cloth.warps"], 17)
        self.assertEqual(scene["time.dt_s"], 0.001)
        self.assertEqual(scene.to_dict()["yarn_types"]["yarn2"]["stretch_modulus_Pa"], 170000.0)
        self.assertFalse(scene.edited)
        with self.assertRaises(KeyError):
            scene["time.rtol"]  # not written: the default applies

    def test_edit_takes_effect(self):
        scene = weavelab.load_scene(HANGING_WIND)
        scene["time.dt_s"] = 0.002
        scene["yarn_types.yarn1.density_kg_per_m"] = 0.003
        self.assertEqual(scene.dt_s, 0.002)
        self.assertIn("0.003", scene.toml)
        self.assertTrue(scene.edited)

    def test_bad_value_names_the_key(self):
        scene = weavelab.load_scene(HANGING_WIND)
        with self.assertRaises(weavelab.SceneError) as e:
            scene["cloth.radius_m"] = -1.0
        self.assertEqual(e.exception.key, "cloth.radius_m")
        self.assertIn("key 'cloth.radius_m'", str(e.exception))
        self.assertIn("got -1", str(e.exception))
        self.assertEqual(scene["cloth.radius_m"], 0.0005)  # a refused edit leaves the scene as it was

    def test_unknown_key_names_the_key(self):
        scene = weavelab.load_scene(HANGING_WIND)
        with self.assertRaises(weavelab.SceneError) as e:
            scene["time.dtt_s"] = 0.001
        self.assertIn("time.dtt_s", str(e.exception))
        self.assertIsInstance(e.exception, ValueError)

    def test_bad_file_names_file_and_line(self):
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "bad.toml")
            with open(path, "w") as f:
                f.write("[cloth]\nwarps = 17\nspacing_m = -2.0\n")
            with self.assertRaises(weavelab.SceneError) as e:
                weavelab.load_scene(path)
            self.assertEqual((e.exception.file, e.exception.line, e.exception.key), (path, 3, "cloth.spacing_m"))

    def test_scene_from_dict(self):
        scene = weavelab.Scene({"cloth": {"warps": 5, "wefts": 5}, "time": {"duration_s": 0.01}})
        self.assertEqual((scene.warps, scene.duration_s), (5, 0.01))
        with self.assertRaises(weavelab.SceneError) as e:
            weavelab.Scene({"cloth": {"warps": 2}})
        self.assertEqual(e.exception.key, "cloth.warps")

    def test_rule_between_keys_in_an_edit(self):
        scene = weavelab.load_scene(HANGING_WIND)
        with self.assertRaises(weavelab.SceneError) as e:
            scene["time.duration_s"] = 0.002  # below the scene's output interval: a scene file is not forgiven
        self.assertIn("time.", e.exception.key)
        scene.update({"time.duration_s": 0.002, "time.output_interval_s": 0.001})  # together they are fine
        self.assertEqual(scene.output_interval_s, 0.001)


class RunArguments(unittest.TestCase):
    def test_short_duration_shrinks_the_interval(self):
        scene = small_scene(weavelab)
        self.assertEqual(scene.output_interval_s, 0.005)
        run = weavelab.run(scene, duration=0.002)
        self.assertEqual(run.outcome, "ok")
        self.assertEqual(list(run.times), [0.0, 0.002])
        self.assertEqual(run.summary["scene"]["output_interval_s"], 0.002)
        self.assertEqual(scene.output_interval_s, 0.005)  # the Scene itself is left as it was

    def test_shrinking_says_so(self):
        script = ("import weavelab, support; "
                  "weavelab.run(support.small_scene(weavelab), duration=0.002)")
        done = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, check=True,
                              cwd=os.path.dirname(os.path.abspath(__file__)))
        self.assertIn("shorter than the scene's output interval; frames every 0.002 s (was 0.005 s)", done.stderr)

    def test_contradiction_stays_an_error(self):
        with self.assertRaises(weavelab.SettingError) as e:
            weavelab.run(small_scene(weavelab), duration=0.002, output_interval=0.004)
        self.assertIn("argument '", str(e.exception))

    def test_unknown_integrator_in_an_edited_scene(self):
        scene = small_scene(weavelab)
        scene["time.integrator"] = "leapfrog"  # a name only the run checks
        with self.assertRaises(weavelab.SceneError) as e:
            weavelab.run(scene)
        self.assertEqual((e.exception.key, e.exception.line), ("time.integrator", 0))
        self.assertIn("leapfrog", str(e.exception))
        with self.assertRaises(weavelab.SceneError):
            weavelab.Simulation(scene)

    def test_bad_argument_names_it(self):
        with self.assertRaises(weavelab.SettingError) as e:
            weavelab.run(small_scene(weavelab), dt=float("nan"))
        self.assertIn("argument 'dt'", str(e.exception))
        with self.assertRaises(weavelab.SettingError) as e:
            weavelab.run(small_scene(weavelab), integrator="leapfrog")
        self.assertIn("leapfrog", str(e.exception))


class KnitsOnlyTheModelRefuses(unittest.TestCase):
    """A knit whose keys are each in range but whose periodic rest tile does not relax
    (a stitch-length stiffness 10^10 times the yarn's): weavelab.SceneError at the file's
    [cloth.pattern] line, or for an edited scene at its origin (line 0), from Model,
    Simulation and run alike."""
    KNIT = ("[cloth]\nspacing_m = 2e-3\nradius_m = 2e-4\nsliding = true\n[cloth.pattern]\n"
            "kind = \"stockinette\"\ncourses = 3\nwales = 3\n[knit]\nstitch_length_stiffness_N = {}\n"
            "[time]\nduration_s = 0.004\noutput_interval_s = 0.002\n")

    def expect_refused(self, scene, file, line):
        for make in (weavelab.Model, weavelab.Simulation, weavelab.run):
            with self.assertRaises(weavelab.SceneError) as e:
                make(scene)
            self.assertEqual((e.exception.file, e.exception.line, e.exception.key), (file, line, "cloth.pattern"))
            self.assertIn("knit.stitch_length_stiffness_N = 1e+09", str(e.exception))
            self.assertIn("periodic rest tile relaxes", str(e.exception))

    def test_from_a_file_and_edited(self):
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "stiff.toml")
            with open(path, "w") as f:
                f.write(self.KNIT.format("1e9"))
            self.expect_refused(weavelab.load_scene(path), path, 6)
            with open(path, "w") as f:
                f.write(self.KNIT.format("0.1"))
            edited = weavelab.load_scene(path)
            edited["knit.stitch_length_stiffness_N"] = 1e9
            self.expect_refused(edited, path, 0)


if __name__ == "__main__":
    unittest.main()
