"""The index of the studies (experiments/common/study_index.py): one line per
study from its RESULTS.md metadata, pending and missing studies marked, paths
relative to the index and to the README, and the README block between its
markers rewritten (a README without markers left alone)."""
import os
import subprocess
import sys
import tempfile
import unittest

from support import SOURCE_DIR

COMMON = os.path.join(SOURCE_DIR, "experiments", "common")
sys.path.insert(0, COMMON)
import results  # noqa: E402

SCRIPT = os.path.join(COMMON, "study_index.py")


def write(path, text):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w", encoding="utf-8") as f:
        f.write(text)


class StudyIndex(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.root = self.tmp.name
        exp = os.path.join(self.root, "experiments")
        table = os.path.join(self.root, "t.csv")
        write(table, "model,dt_s\nyarn,0.001\n")
        figure = os.path.join(self.root, "chart.png")
        write(figure, "not really a picture")
        self.done = os.path.join(exp, "alpha", "RESULTS.md")
        os.makedirs(os.path.dirname(self.done))
        results.write_results(self.done, "alpha", "Alpha | study", [results.Figure("Chart", figure)], ["cmd"],
                              headline=results.Headline("step {value} s", table, column="dt_s"))
        self.pending = os.path.join(exp, "beta", "RESULTS.md")
        os.makedirs(os.path.dirname(self.pending))
        results.write_pending(self.pending, "beta", "Beta study", "snakemake beta", "3 h of CPU")
        self.missing = os.path.join(exp, "gamma", "RESULTS.md")
        self.index = os.path.join(exp, "INDEX.md")
        self.readme = os.path.join(self.root, "README.md")

    def tearDown(self):
        self.tmp.cleanup()

    def run_index(self, *extra):
        return subprocess.run([sys.executable, SCRIPT, self.index, self.done, self.pending, self.missing, *extra],
                              capture_output=True, text=True)

    def test_index_lines(self):
        p = self.run_index()
        self.assertEqual(p.returncode, 0, p.stderr)
        with open(self.index, encoding="utf-8") as f:
            lines = [line for line in f.read().splitlines() if line.startswith("| ")]
        self.assertEqual(len(lines), 4)  # header and one line per study, in the order given
        entry = results.read_index_entry(self.done)
        self.assertEqual(lines[1], f"| [Alpha \\| study](alpha/RESULTS.md) | step 0.001 s | "
                                   f'<img src="alpha/figures/chart.png" width="240" alt="Alpha \\| study"> | '
                                   f"`{entry['revision']}`, {entry['date']} |")
        self.assertTrue(lines[2].startswith("| [Beta study](beta/RESULTS.md) | *not yet run at this revision* |  |"))
        self.assertEqual(lines[3], "| gamma | *not yet run* |  |  |")

    def test_readme_block(self):
        write(self.readme, "Intro.\n<!-- results-index:start -->\nold text\n<!-- results-index:end -->\nAfter.\n")
        p = self.run_index("--readme", self.readme)
        self.assertEqual(p.returncode, 0, p.stderr)
        with open(self.readme, encoding="utf-8") as f:
            text = f.read()
        self.assertTrue(text.startswith("Intro.\n<!-- results-index:start -->\n| study |"))
        self.assertTrue(text.endswith("<!-- results-index:end -->\nAfter.\n"))
        self.assertNotIn("old text", text)
        self.assertIn("(experiments/alpha/RESULTS.md)", text)  # paths relative to the README
        self.assertIn('src="experiments/alpha/figures/chart.png"', text)

    def test_readme_without_markers_is_left_alone(self):
        write(self.readme, "No markers here.\n")
        p = self.run_index("--readme", self.readme)
        self.assertEqual(p.returncode, 0, p.stderr)
        with open(self.readme, encoding="utf-8") as f:
            self.assertEqual(f.read(), "No markers here.\n")

    def test_bad_input(self):
        write(self.readme, "<!-- results-index:end -->\n<!-- results-index:start -->\n")
        p = self.run_index("--readme", self.readme)
        self.assertEqual(p.returncode, 2)
        self.assertIn("expected '<!-- results-index:start -->' before", p.stderr)
        self.assertFalse(os.path.exists(self.index))  # nothing written
        write(self.pending, "# Hand-written, no metadata\n")
        p = self.run_index()
        self.assertEqual(p.returncode, 2)
        self.assertIn(f"{self.pending}: line 1: expected the metadata comment", p.stderr)


if __name__ == "__main__":
    unittest.main()
