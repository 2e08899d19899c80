"""The studies as one workflow (Snakefile at the root, experiments/README.md):
the dry run lists every study, `index` alone runs no study, `studies=` chooses some, and the stability study
runs end to end on a 5×5 cloth into a temporary folder: cells, merge, chart and
RESULTS.md with its figure, table, cost and commands."""
import csv
import glob
import os
import re
import shutil
import subprocess
import sys
import tempfile
import unittest

from support import CLI, SOURCE_DIR

sys.path.insert(0, os.path.join(SOURCE_DIR, "experiments", "common"))
import results  # noqa: E402

SNAKEMAKE = shutil.which("snakemake")
PYTHON_DIR = os.environ.get("PYTHONPATH", os.path.join(SOURCE_DIR, "build", "python")).split(os.pathsep)[0]
STUDIES = sorted(os.path.basename(os.path.dirname(p)) for p in glob.glob(os.path.join(SOURCE_DIR, "experiments", "*",
                                                                                      "Snakefile")))


def snakemake(*args, config=()):
    """snakemake from the repository root with this build's program and module, and `config` besides."""
    return subprocess.run([SNAKEMAKE, "--nolock", *args, "--config", f"weavelab={CLI}", f"python={PYTHON_DIR}",
                           *config], cwd=SOURCE_DIR, capture_output=True, text=True)


def jobs(output):
    """Rule names of the job-stats table of a dry run."""
    return set(re.findall(r"^(\w+)\s+\d+\s+\d+\s+\d+$", output, flags=re.M))


@unittest.skipUnless(SNAKEMAKE, "snakemake (Debian package snakemake) not installed")
class RootWorkflow(unittest.TestCase):
    def test_dry_run_lists_every_study(self):
        p = snakemake("-n", "--forceall", "--cores", "1")
        self.assertEqual(p.returncode, 0, p.stdout + p.stderr)
        listed = jobs(p.stdout)
        self.assertGreater(len(STUDIES), 0)
        for study in STUDIES:
            self.assertIn(f"{study}_results", listed, study)
        self.assertIn("studies_then_index", listed)

    def test_the_index_alone_runs_no_study(self):
        p = snakemake("-n", "--forceall", "--cores", "1", "index")
        self.assertEqual(p.returncode, 0, p.stdout + p.stderr)
        self.assertEqual(jobs(p.stdout) - {"total"}, {"index"})

    def test_chosen_studies(self):
        p = snakemake("-n", "--forceall", "--cores", "1", config=["studies=stability"])
        self.assertEqual(p.returncode, 0, p.stdout + p.stderr)
        self.assertEqual({j for j in jobs(p.stdout) if j.endswith("_results")}, {"stability_results"})
        p = snakemake("-n", "--cores", "1", config=["studies=stability,no_such_study"])
        self.assertNotEqual(p.returncode, 0)
        self.assertIn("config key 'studies': no study no_such_study", p.stdout + p.stderr)


def small_stability_scene(path):
    """experiments/scenes/stability_9.toml at 5×5 crossings, the second handle on the new corner."""
    with open(os.path.join(SOURCE_DIR, "experiments", "scenes", "stability_9.toml"), encoding="utf-8") as f:
        text = f.read()
    for old, new in (("warps = 9", "warps = 5"), ("wefts = 9", "wefts = 5"), ("node = [8, 0]", "node = [4, 0]")):
        if old not in text:
            raise AssertionError(f"stability_9.toml: no '{old}' to replace")
        text = text.replace(old, new)
    with open(path, "w", encoding="utf-8") as f:
        f.write(text)


@unittest.skipUnless(SNAKEMAKE, "snakemake (Debian package snakemake) not installed")
class StabilityEndToEnd(unittest.TestCase):
    def test_cells_merge_chart_and_results(self):
        with tempfile.TemporaryDirectory() as tmp:
            scene = os.path.join(tmp, "stability_5.toml")
            small_stability_scene(scene)
            out, report = os.path.join(tmp, "out"), os.path.join(tmp, "study", "RESULTS.md")
            study = (f"stability={{scene: {scene}, models: [yarn], integrators: [be-linear, symplectic], "
                     f"multipliers: [1], options: '--duration 0.01 --bisections 2', out: {out}, results: {report}}}")
            p = snakemake("-s", "experiments/stability/Snakefile", "--cores", "2", config=[study])
            self.assertEqual(p.returncode, 0, p.stdout + p.stderr)
            with open(os.path.join(out, "stability.csv"), newline="", encoding="utf-8") as f:
                rows = list(csv.DictReader(f))
            self.assertEqual([(r["model"], r["integrator"]) for r in rows], [("yarn", "be-linear"), ("yarn", "symplectic")])
            with open(report, encoding="utf-8") as f:
                text = f.read()
            for r in rows:  # every merged row is in the table, as the writer formats it
                cells = [results.format_cell(r[c], 4) for c in rows[0].keys()]
                self.assertIn("| " + " | ".join(c.replace("|", "\\|") for c in cells) + " |", text)
            self.assertTrue(os.path.isfile(os.path.join(tmp, "study", "figures", "stability.png")))
            self.assertIn("![Largest bounded step per integrator, model and stiffness](figures/stability.png)", text)
            for integrator in ("be-linear", "symplectic"):
                self.assertIn(f"{CLI} stability {scene} --models yarn --integrators {integrator} --multipliers 1 "
                              f"--duration 0.01 --bisections 2 --quiet --out {out}/cells/", text)
                self.assertIn(f"| {out}/benchmarks/yarn_{integrator}_1.tsv |", text)
            entry = results.read_index_entry(report)
            self.assertEqual((entry["study"], entry["figure"]), ("stability", "figures/stability.png"))


if __name__ == "__main__":
    unittest.main()
