"""experiments/common/scene_variant.py, the studies' variants of a scene: a key
replaced in its table with the line's comment kept, a key added to a table that
lacks it, a table appended, a nested table, a key removed, the obstacles
removed; bad input is
exit 2 with the key named and nothing written."""
import os
import subprocess
import sys
import tempfile
import tomllib
import unittest

from support import SOURCE_DIR

SCRIPT = os.path.join(SOURCE_DIR, "experiments", "common", "scene_variant.py")
SCENE = """# a scene
[cloth]
warps = 5
spacing_m = 0.001   # L

[cloth.pattern]
kind = "plain"

[[obstacles]]
shape = "sphere"
radius_m = 0.004

[[obstacles]]
shape = "plane"

[contact]
friction_coefficient = 0.05          # mu
warps = 7
"""


class SceneVariant(unittest.TestCase):
    def variant(self, *args):
        tmp = tempfile.TemporaryDirectory()
        self.addCleanup(tmp.cleanup)
        scene, out = os.path.join(tmp.name, "scene.toml"), os.path.join(tmp.name, "out", "variant.toml")
        with open(scene, "w") as f:
            f.write(SCENE)
        r = subprocess.run([sys.executable, SCRIPT, scene, out, *args], capture_output=True, text=True)
        if not os.path.exists(out):
            return r, None
        with open(out) as f:
            return r, f.read()

    def test_keys_set_added_and_tables_appended(self):
        r, text = self.variant("--set", "contact.friction_coefficient=0.1", "--set", "cloth.radius_m=0.0005",
                               "--set", "cloth.pattern.kind=\"twill\"", "--set", "self_contact.enabled=true")
        self.assertEqual(r.returncode, 0, r.stderr)
        scene = tomllib.loads(text)
        self.assertEqual(scene["contact"]["friction_coefficient"], 0.1)
        self.assertEqual(scene["contact"]["warps"], 7)  # the same key name in another table is left alone
        self.assertEqual(scene["cloth"]["warps"], 5)
        self.assertEqual(scene["cloth"]["radius_m"], 0.0005)
        self.assertEqual(scene["cloth"]["pattern"]["kind"], "twill")
        self.assertEqual(scene["self_contact"], {"enabled": True})
        self.assertEqual(len(scene["obstacles"]), 2)
        self.assertIn("friction_coefficient = 0.1          # mu", text)
        self.assertTrue(text.startswith("# a scene\n"))

    def test_unset_removes_the_key_of_that_table_only(self):
        r, text = self.variant("--unset", "contact.warps", "--unset", "time.settle_after_s")
        self.assertEqual(r.returncode, 0, r.stderr)
        scene = tomllib.loads(text)
        self.assertNotIn("warps", scene["contact"])
        self.assertEqual(scene["cloth"]["warps"], 5)
        self.assertEqual(scene["contact"]["friction_coefficient"], 0.05)
        self.assertNotIn("time", scene)  # a key the scene does not set stays unset

    def test_without_obstacles(self):
        r, text = self.variant("--without-obstacles")
        self.assertEqual(r.returncode, 0, r.stderr)
        scene = tomllib.loads(text)
        self.assertNotIn("obstacles", scene)
        self.assertEqual(scene["contact"]["friction_coefficient"], 0.05)
        self.assertEqual(scene["cloth"]["pattern"]["kind"], "plain")

    def test_bad_input_is_exit_2_and_writes_nothing(self):
        for args, words in ((["--set", "contact.friction_coefficient=abc"], ["contact.friction_coefficient", "abc"]),
                            (["--set", "warps=3"], ["warps=3", "TABLE.KEY=VALUE"]),
                            (["--set", "obstacles.shape=\"box\""], ["not TOML"]),
                            (["--unset", "warps"], ["--unset 'warps'", "TABLE.KEY"])):
            r, text = self.variant(*args)
            self.assertEqual(r.returncode, 2, args)
            for w in words:
                self.assertIn(w, r.stderr)
            self.assertIsNone(text)


if __name__ == "__main__":
    unittest.main()
