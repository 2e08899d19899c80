"""The worked example of docs/python.md runs as written, from the repository root."""
import os
import re
import subprocess
import sys
import unittest

from support import SOURCE_DIR


class DocsExample(unittest.TestCase):
    def test_worked_example(self):
        with open(os.path.join(SOURCE_DIR, "docs", "python.md")) as f:
            text = f.read()
        match = re.search(r"<!-- example -->\n```python\n(.*?)```", text, re.S)
        self.assertIsNotNone(match, "docs/python.md: no ```python block after <!-- example -->")
        done = subprocess.run([sys.executable, "-c", match.group(1)], cwd=SOURCE_DIR, capture_output=True,
                              text=True, timeout=600)
        self.assertEqual(done.returncode, 0, done.stderr)
        lines = done.stdout.splitlines()
        sweep = [line for line in lines if line.startswith("wind ")]
        self.assertEqual(len(sweep), 3, done.stdout)
        # A stronger wind pushes the cloth further along +y, by more than the runs' time errors.
        deflections = [float(re.search(r"deflection (\S+) mm", line).group(1)) for line in sweep]
        errors = [float(re.search(r"time error <= (\S+) mm", line).group(1)) for line in sweep]
        for k in range(2):
            self.assertGreater(deflections[k + 1] - deflections[k], errors[k] + errors[k + 1], sweep)
        check = next(line for line in lines if line.startswith("dfdq"))
        self.assertLess(float(check.split(":")[1]), 1e-3, check)


if __name__ == "__main__":
    unittest.main()
