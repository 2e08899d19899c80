"""The scale study's merge (experiments/scale/scripts/merge_scale.py) on synthetic cells: a cell
its CPU limit stopped (no CSV row, SIGXCPU in its /usr/bin/time -v report) becomes a row with
that status, the CPU time and peak it reached, and stays out of the ratios, the breakdown and the
estimate table (each other cell's estimate over its peak); a cell with neither a row nor that
report is exit 2."""
import csv
import os
import subprocess
import sys
import tempfile
import unittest

from support import SOURCE_DIR

SCRIPT = os.path.join(SOURCE_DIR, "experiments", "scale", "scripts", "merge_scale.py")
COLUMNS = ["scene", "model", "requested", "solver", "dofs", "nnz", "steps", "step_ms", "step_cpu_ms", "krylov_per_step",
           "factorizations_per_step", "rss_start_mb", "peak_model_mb", "rss_model_mb", "rss_initialized_mb",
           "rss_end_mb", "peak_mb", "solver_matrices_mb", "preconditioner_mb", "krylov_mb", "scatter_plans_mb",
           "pattern_mb", "estimate_mb"]


def report(user_s, rss_kb, signal=None):
    head = f"\tCommand terminated by signal {signal}\n" if signal else ""
    return (head + f"\tUser time (seconds): {user_s}\n\tSystem time (seconds): 1.00\n"
            f"\tMaximum resident set size (kbytes): {rss_kb}\n\tExit status: 0\n")


def write_cell(folder, name, step_ms=None, user_s=10.0, rss_kb=1000, signal=None):
    with open(os.path.join(folder, name + ".csv"), "w", newline="") as f:
        if step_ms is not None:
            w = csv.writer(f, lineterminator="\n")
            w.writerow(COLUMNS)
            w.writerow(["s.toml", "yarn", "x", "x", 1000, 5000, 2, step_ms, step_ms / 2, 8, 0.5, 10, 50, 40, 60, 70, 80,
                        5, 6, 7, 8, 9, 100])
    with open(os.path.join(folder, name + ".time"), "w") as f:
        f.write(report(user_s, rss_kb, signal))
    return os.path.join(folder, name + ".csv")


def merge(folder, cells):
    out = {k: os.path.join(folder, k + ".out.csv") for k in ("table", "ratios", "breakdown", "estimates")}
    proc = subprocess.run([sys.executable, SCRIPT, "--table", out["table"], "--ratios", out["ratios"], "--breakdown",
                           out["breakdown"], "--estimates", out["estimates"], "--cells", *cells],
                          capture_output=True, text=True)
    rows = {}
    if proc.returncode == 0:
        for k, path in out.items():
            with open(path, newline="") as f:
                rows[k] = list(csv.DictReader(f))
    return proc, rows


class ScaleMerge(unittest.TestCase):
    def test_a_stopped_cell_is_a_row_out_of_the_ratios(self):
        with tempfile.TemporaryDirectory() as tmp:
            cells = [write_cell(tmp, "17_gmres", step_ms=4.0), write_cell(tmp, "17_amg", step_ms=3.0),
                     write_cell(tmp, "33_gmres", user_s=599.0, rss_kb=2000000, signal=24),
                     write_cell(tmp, "33_amg", step_ms=12.0)]
            proc, rows = merge(tmp, cells)
            self.assertEqual(proc.returncode, 0, proc.stderr)
            by = {(r["size"], r["solver"]): r for r in rows["table"]}
            self.assertEqual(by[("33", "gmres")]["status"], "stopped by the CPU limit after 600 s CPU")
            self.assertEqual(by[("33", "gmres")]["max_rss_mb"], "2048.0")
            self.assertEqual(by[("33", "gmres")]["step_ms"], "")
            self.assertEqual(by[("33", "amg")]["status"], "ok")
            self.assertEqual([r["size"] for r in rows["ratios"]], ["17"])
            self.assertEqual(rows["ratios"][0]["step_ratio"], "0.750")
            # The breakdown is of the largest size measured by a cell that finished: 33 (amg alone).
            self.assertEqual({r["size"] for r in rows["breakdown"]}, {"33×33"})
            self.assertNotIn("gmres", rows["breakdown"][0])
            # The estimate (100 MB) over each finished cell's peak as its table row gives it (1000 kB of
            # /usr/bin/time -v: 1.0 MB at the table's 0.1 MB).
            self.assertEqual([(r["size"], r["solver"]) for r in rows["estimates"]],
                             [("17", "amg"), ("17", "gmres"), ("33", "amg")])
            self.assertEqual({r["estimate_over_peak"] for r in rows["estimates"]}, {"100.000"})

    def test_a_cell_without_a_row_that_was_not_stopped_fails(self):
        with tempfile.TemporaryDirectory() as tmp:
            proc, _ = merge(tmp, [write_cell(tmp, "17_gmres", signal=9)])
            self.assertEqual(proc.returncode, 2)
            self.assertIn("17_gmres.csv", proc.stderr)


if __name__ == "__main__":
    unittest.main()
