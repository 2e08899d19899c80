"""The sweeps' merge step (experiments/common/merge_parts.py): the parts of a
sweep become the folder one run of the command would have written."""
import csv
import json
import os
import subprocess
import sys
import tempfile
import unittest

from support import SOURCE_DIR

MERGE = os.path.join(SOURCE_DIR, "experiments", "common", "merge_parts.py")


def write_part(folder, model, integrator, message):
    os.makedirs(folder)
    with open(os.path.join(folder, "stability.csv"), "w", newline="") as f:
        w = csv.writer(f, lineterminator="\n")
        w.writerow(["model", "integrator", "message"])
        w.writerow([model, integrator, message])
    with open(os.path.join(folder, "stability.json"), "w") as f:
        json.dump({"experiment": "stability", "parameters": {"models": [model], "integrators": [integrator],
                                                             "bisections": 8},
                   "cells": 1, "wall_s": 2.0, "started_utc": "2026-01-01T00:00:0%dZ" % len(integrator),
                   "finished_utc": "2026-01-01T00:01:00Z"}, f)


class MergeParts(unittest.TestCase):
    def test_parts_become_one_folder(self):
        with tempfile.TemporaryDirectory() as tmp:
            a, b = os.path.join(tmp, "a"), os.path.join(tmp, "b")
            write_part(a, "yarn", "be-linear", "ok")
            write_part(b, "fem", "sdirk2", "diverged: speed 12, bound 10")  # a comma: quoted in the CSV
            out = os.path.join(tmp, "out")
            subprocess.run([sys.executable, MERGE, out, "stability", a, b], check=True)
            with open(os.path.join(out, "stability.csv"), newline="") as f:
                rows = list(csv.DictReader(f))
            self.assertEqual([(r["model"], r["integrator"], r["message"]) for r in rows],
                             [("yarn", "be-linear", "ok"), ("fem", "sdirk2", "diverged: speed 12, bound 10")])
            with open(os.path.join(out, "stability.json")) as f:
                meta = json.load(f)
            self.assertEqual(meta["parameters"]["models"], ["yarn", "fem"])
            self.assertEqual(meta["parameters"]["integrators"], ["be-linear", "sdirk2"])
            self.assertEqual(meta["parameters"]["bisections"], 8)
            self.assertEqual((meta["cells"], meta["wall_s"], len(meta["parts"])), (2, 4.0, 2))

    def test_differing_columns_are_refused(self):
        with tempfile.TemporaryDirectory() as tmp:
            a, b = os.path.join(tmp, "a"), os.path.join(tmp, "b")
            write_part(a, "yarn", "be-linear", "ok")
            write_part(b, "fem", "sdirk2", "ok")
            with open(os.path.join(b, "stability.csv"), "w") as f:
                f.write("model,other\nfem,1\n")
            done = subprocess.run([sys.executable, MERGE, os.path.join(tmp, "out"), "stability", a, b],
                                  capture_output=True, text=True)
            self.assertNotEqual(done.returncode, 0)
            self.assertIn("differ", done.stderr)


if __name__ == "__main__":
    unittest.main()
