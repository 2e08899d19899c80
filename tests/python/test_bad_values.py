"""Values a scene cannot hold, and times a simulation cannot reach: each refused
with an error naming the key (weavelab.SceneError) or the time, never a crash of
the interpreter nor a run that does not end."""
import os
import subprocess
import sys
import unittest

import weavelab
from support import HANGING_WIND, small_scene

HERE = os.path.dirname(os.path.abspath(__file__))


def in_child(script):
    """Runs `script` in a fresh interpreter: a crash there is a failed test here, not a lost run."""
    return subprocess.run([sys.executable, "-c", "import weavelab, support\n" + script], capture_output=True,
                          text=True, cwd=HERE, timeout=120)


class BadSceneValues(unittest.TestCase):
    def refused(self, script, key):
        """`script` sets the value; it must raise SceneError naming `key`, with the interpreter alive."""
        done = in_child("try:\n" + "".join("    " + line + "\n" for line in script.splitlines()) +
                        "except weavelab.SceneError as e:\n    print('SceneError', e.key, '|', e)\n")
        self.assertEqual(done.returncode, 0, done.stderr)
        self.assertTrue(done.stdout.startswith("SceneError " + key + " |"), done.stdout + done.stderr)
        return done.stdout

    def test_a_dict_that_contains_itself(self):
        out = self.refused("d = {'warps': 5}\nd['self'] = d\nweavelab.Scene({'cloth': d})", "cloth.self")
        self.assertIn("got a dict that contains itself", out)

    def test_a_list_that_contains_itself(self):
        out = self.refused("s = weavelab.load_scene(support.HANGING_WIND)\nl = [1.0]\nl.append(l)\n"
                           "s['wind.velocity_m_per_s'] = l", r"wind.velocity_m_per_s[1]")
        self.assertIn("got a list that contains itself", out)

    def test_dicts_nested_200000_deep(self):
        out = self.refused("d = {}\nfor _ in range(200000):\n    d = {'a': d}\nweavelab.Scene({'cloth': d})",
                           "cloth" + ".a" * 31)
        self.assertIn("nested deeper than 32 levels", out)

    def test_an_object_whose_tolist_is_itself(self):
        self.refused("class Odd:\n    def tolist(self):\n        return self\n"
                     "s = weavelab.load_scene(support.HANGING_WIND)\ns['cloth.warps'] = Odd()", "cloth.warps")

    def test_an_integer_beyond_64_bits(self):
        scene = weavelab.load_scene(HANGING_WIND)
        for big, says in ((10**30, "got 1000000000000000000000000000000"), (-2**63 - 1, "got -9223372036854775809"),
                          (10**1000, "got an integer of 3322 bits")):
            with self.assertRaises(weavelab.SceneError) as e:
                scene["cloth.warps"] = big
            self.assertEqual(e.exception.key, "cloth.warps")
            self.assertIn(says, str(e.exception))
        with self.assertRaises(weavelab.SceneError) as e:
            scene.update({"time.duration_s": 1.0, "cloth.wefts": 2**64})
        self.assertEqual(e.exception.key, "cloth.wefts")
        self.assertEqual(scene["cloth.warps"], 17)  # a refused edit leaves the scene as it was

    def test_none(self):
        scene = weavelab.load_scene(HANGING_WIND)
        with self.assertRaises(weavelab.SceneError) as e:
            scene["time.dt_s"] = None
        self.assertEqual((e.exception.key, e.exception.value), ("time.dt_s", "None"))
        self.assertIn("delete the key to have its default", str(e.exception))
        with self.assertRaises(weavelab.SceneError) as e:
            weavelab.Scene({"cloth": {"warps": 5}, "time": None})
        self.assertEqual(e.exception.key, "time")
        with self.assertRaises(weavelab.SceneError) as e:
            scene.update({"handles": [{"node": [0, None]}]})
        self.assertEqual(e.exception.key, "handles[0].node[1]")

    def test_another_type(self):
        scene = weavelab.load_scene(HANGING_WIND)
        with self.assertRaises(weavelab.SceneError) as e:
            scene["cloth.warps"] = object()
        self.assertEqual((e.exception.key, e.exception.value), ("cloth.warps", "a value of type object"))

    def test_a_value_shared_without_a_cycle_is_fine(self):
        v = [0.0, 1.0, 0.0]  # one list at two keys is no cycle
        scene = weavelab.load_scene(HANGING_WIND)
        scene.update({"wind.velocity_m_per_s": v, "gravity.acceleration_m_per_s2": v})
        self.assertEqual((scene["wind.velocity_m_per_s"], scene["gravity.acceleration_m_per_s2"]), (v, v))


class SimulationTimes(unittest.TestCase):
    def test_a_time_that_is_not_finite_or_past_the_end(self):
        scene = small_scene(weavelab)  # 0.02 s
        sim = weavelab.Simulation(scene)
        for t in (float("inf"), float("nan"), 0.0200001, 1e300):
            with self.assertRaises(ValueError) as e:
                sim.advance_to(t)
            self.assertIn("expected a time from Simulation.t (0 s) to the scene's time.duration_s (0.02 s)",
                          str(e.exception))
        self.assertEqual(sim.t, 0.0)
        self.assertEqual(sim.advance_to(0.02)["outcome"], "ok")
        self.assertEqual(sim.t, 0.02)
        with self.assertRaises(ValueError) as e:
            sim.step()
        self.assertIn("nothing is left to step", str(e.exception))

    def test_steps_end_at_the_duration(self):
        scene = small_scene(weavelab)  # dt 1 ms
        scene.update({"time.duration_s": 0.0025, "time.output_interval_s": 0.0025})  # two steps and a half one
        sim = weavelab.Simulation(scene)
        for _ in range(3):
            self.assertEqual(sim.step()["outcome"], "ok")
        self.assertEqual(sim.t, 0.0025)


if __name__ == "__main__":
    unittest.main()
