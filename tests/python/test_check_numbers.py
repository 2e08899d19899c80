"""tools/check_numbers.py: a hand-typed measurement in README or docs fails, a clean text passes."""
import os
import subprocess
import sys
import tempfile
import unittest

SOURCE_DIR = os.environ.get("WEAVELAB_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))
SCRIPT = os.path.join(SOURCE_DIR, "tools", "check_numbers.py")

CLEAN = """# A page

The step matrix is factorized once per step; the speed study reports the cost
([experiments/speed/RESULTS.md](../experiments/speed/RESULTS.md)). A 17×17 cloth,
a 16 × 16 patch, `--rtol 1e-4`, x86-64, §11 and 2s(1 + r^m) are no measurements.
"""


class CheckNumbers(unittest.TestCase):
    def setUp(self):
        self.root = tempfile.TemporaryDirectory()
        os.makedirs(os.path.join(self.root.name, "docs"))
        self.allow = os.path.join(self.root.name, "allow.txt")
        self.write("allow.txt", "# nothing allowed\n")

    def tearDown(self):
        self.root.cleanup()

    def write(self, name, text):
        with open(os.path.join(self.root.name, name), "w", encoding="utf-8") as f:
            f.write(text)

    def check(self, readme, page=CLEAN):
        self.write("README.md", readme)
        self.write(os.path.join("docs", "page.md"), page)
        return subprocess.run([sys.executable, SCRIPT, "--root", self.root.name, "--allow", self.allow],
                              capture_output=True, text=True, timeout=60)

    def test_clean_files_pass(self):
        done = self.check(CLEAN)
        self.assertEqual(done.returncode, 0, done.stdout + done.stderr)
        self.assertEqual(done.stdout, "")

    def test_hand_typed_timing_fails_with_file_and_line(self):
        done = self.check(CLEAN, CLEAN + "\nOne be-linear step took 5.09 ms on the 2-core machine.\n")
        self.assertEqual(done.returncode, 1, done.stdout + done.stderr)
        self.assertIn("docs/page.md:7: '5.09 ms'", done.stdout)

    def test_each_unit_kind_is_caught(self):
        for text, hit in (("a speed-up of 1.9×", "1.9×"), ("3.4 mm from the converged motion", "3.4 mm"),
                          ("peak 3.85 GB", "3.85 GB"), ("898 MB", "898 MB"), ("within 1 %", "1 %"),
                          ("12.21 Hz", "12.21 Hz"), ("46 µJ", "46 µJ"), ("2.5x faster", "2.5x"),
                          ("16.1 s", "16.1 s"), ("12.7 min", "12.7 min"), ("1 317 ms", "1 317 ms"),
                          ("9.4·10⁻¹³ m apart", "9.4·10⁻¹³ m")):
            with self.subTest(text=text):
                done = self.check(CLEAN + "\n" + text + "\n")
                self.assertEqual(done.returncode, 1, text)
                self.assertIn(f"README.md:7: '{hit}' in: {text}", done.stdout)

    def test_generated_index_is_skipped(self):
        readme = CLEAN + ("<!-- results-index:start -->\n| speed | one step 5.09 ms |\n"
                          "<!-- results-index:end -->\n")
        self.assertEqual(self.check(readme).returncode, 0)
        after = readme + "A step took 5.09 ms.\n"
        self.assertEqual(self.check(after).returncode, 1)

    def test_unclosed_index_fails(self):
        done = self.check(CLEAN + "<!-- results-index:start -->\n")
        self.assertEqual(done.returncode, 1)
        self.assertIn("without", done.stdout)

    def test_allow_list_covers_only_its_text(self):
        self.write("allow.txt", "L = 1 mm and R = 0.5 mm :: the authors' constants (Gong et al. 2022)\n")
        done = self.check(CLEAN + "\nL = 1 mm and R = 0.5 mm in the source.\n")
        self.assertEqual(done.returncode, 0, done.stdout)
        done = self.check(CLEAN + "\nL = 1 mm and R = 0.5 mm; a run moved 0.5 mm.\n")
        self.assertEqual(done.returncode, 1)
        self.assertIn("'0.5 mm' in: L = 1 mm and R = 0.5 mm; a run moved 0.5 mm.", done.stdout)

    def test_unused_allow_entry_fails(self):
        self.write("allow.txt", "S = 1000 Pa at 9.8 m/s² :: a constant nobody writes\n")
        done = self.check(CLEAN)
        self.assertEqual(done.returncode, 1)
        self.assertIn("allows nothing", done.stdout)

    def test_allow_entry_without_reason_is_bad_input(self):
        self.write("allow.txt", "L = 1 mm\n")
        done = self.check(CLEAN)
        self.assertEqual(done.returncode, 2)
        self.assertIn("expected 'TEXT :: REASON'", done.stderr)

    def test_repository_passes(self):
        done = subprocess.run([sys.executable, SCRIPT, "--root", SOURCE_DIR], capture_output=True, text=True,
                              timeout=60)
        self.assertEqual(done.returncode, 0, done.stdout + done.stderr)


if __name__ == "__main__":
    unittest.main()
