"""The RESULTS.md writer (experiments/common/results.py): tables, figures,
texts, the headline, the cost of each cell, the commands, the metadata the
index reads, and the RESULTS.md of a study not yet run."""
import csv
import os
import sys
import tempfile
import unittest

from support import SOURCE_DIR

sys.path.insert(0, os.path.join(SOURCE_DIR, "experiments", "common"))
import results  # noqa: E402
from results import Figure, Headline, Table, Text  # noqa: E402

# The smallest valid PNG (1×1, grey): the writer copies figures byte for byte.
PNG = bytes.fromhex("89504e470d0a1a0a0000000d4948445200000001000000010800000000"
                    "3a7e9b550000000a4944415408d76360000000020001e221bc330000000049454e44ae426082")


def write_csv(path, header, rows):
    with open(path, "w", newline="", encoding="utf-8") as f:
        w = csv.writer(f, lineterminator="\n")
        w.writerow(header)
        w.writerows(rows)


class Study(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.dir = self.tmp.name
        self.study = os.path.join(self.dir, "experiments", "toy")
        os.makedirs(self.study)
        self.table = os.path.join(self.dir, "table.csv")
        write_csv(self.table, ["model", "dt_s", "steps", "note"],
                  [["yarn", "0.00123456", "50", "a|b"], ["fem", "2.5e-05", "7", "ok"]])
        self.figure = os.path.join(self.dir, "chart.png")
        with open(self.figure, "wb") as f:
            f.write(PNG)
        self.text = os.path.join(self.dir, "verdict.md")
        with open(self.text, "w", encoding="utf-8") as f:
            f.write("Both bounded.\n\n")
        self.bench = os.path.join(self.dir, "cell.tsv")
        with open(self.bench, "w", encoding="utf-8") as f:
            f.write("s\th:m:s\tmax_rss\tmax_vms\tmax_uss\tmax_pss\tio_in\tio_out\tmean_load\tcpu_time\n"
                    "12.345678\t0:00:12\t101.5\t200\t90\t95\t0\t1\t95.1\t11.98765\n")
        with open(os.path.join(self.study, "about.md"), "w", encoding="utf-8") as f:
            f.write("What the toy study measures.\n")
        self.path = os.path.join(self.study, "RESULTS.md")

    def tearDown(self):
        self.tmp.cleanup()

    def write(self, **kw):
        args = dict(study="toy", title="Toy study",
                    sections=[Table("Steps", self.table, digits=3), Figure("Chart", self.figure, caption="A caption."),
                              Text("Verdict", self.text)],
                    commands=["build/weavelab stability s.toml --models yarn", "build/weavelab stability s.toml --models fem"],
                    benchmarks=[self.bench],
                    headline=Headline("largest step {value} s", self.table, column="dt_s", where={"model": "fem"}))
        args.update(kw)
        results.write_results(self.path, **args)
        with open(self.path, encoding="utf-8") as f:
            return f.read()

    def test_sections_in_order_with_formatted_cells(self):
        text = self.write()
        self.assertIn("| model | dt_s | steps | note |\n|---|---|---|---|\n", text)
        self.assertIn("| yarn | 0.00123 | 50 | a\\|b |", text)  # 3 significant digits, integers kept, | escaped
        self.assertIn("| fem | 2.5e-05 | 7 | ok |", text)
        self.assertIn("![Chart](figures/chart.png)\n", text)
        self.assertIn("A caption.", text)
        self.assertIn("## Verdict\n\nBoth bounded.\n", text)
        self.assertIn("What the toy study measures.", text)
        order = [text.index(s) for s in ("# Toy study", "What the toy study", "## Steps", "## Chart", "## Verdict",
                                         "## Cost of each cell", "## Commands")]
        self.assertEqual(order, sorted(order))
        with open(os.path.join(self.study, "figures", "chart.png"), "rb") as f:
            self.assertEqual(f.read(), PNG)
        self.assertFalse(os.path.exists(self.path + ".tmp"))

    def test_headline_commands_and_cost(self):
        text = self.write()
        self.assertIn("**largest step 2.5e-05 s**", text)
        self.assertIn("```\nbuild/weavelab stability s.toml --models yarn\nbuild/weavelab stability s.toml --models fem\n```",
                      text)
        self.assertIn(f"| {self.bench} | 12.35 | 11.99 | 101.5 |", text)

    def test_index_entry(self):
        self.write()
        entry = results.read_index_entry(self.path)
        self.assertEqual((entry["study"], entry["title"], entry["headline"], entry["figure"]),
                         ("toy", "Toy study", "largest step 2.5e-05 s", "figures/chart.png"))
        self.assertRegex(entry["date"], r"^\d{4}-\d\d-\d\d \d\d:\d\d UTC$")
        self.assertNotIn("pending", entry)

    def test_no_headline_no_figure(self):
        self.write(sections=[Table("Steps", self.table)], headline=None, benchmarks=[])
        entry = results.read_index_entry(self.path)
        self.assertIsNone(entry["headline"])
        self.assertIsNone(entry["figure"])

    def test_missing_column_and_row_are_errors(self):
        with self.assertRaisesRegex(ValueError, "no column wall"):
            self.write(sections=[Table("Steps", self.table, columns=["model", "wall"])])
        with self.assertRaisesRegex(ValueError, "no row with"):
            self.write(headline=Headline("{value}", self.table, column="dt_s", where={"model": "cloth"}))

    def test_a_file_without_metadata_has_no_entry(self):
        with open(self.path, "w", encoding="utf-8") as f:
            f.write("# Hand-written\n")
        self.assertIsNone(results.read_index_entry(self.path))

    def test_pending(self):
        old = os.path.join(self.study, "figures", "old.png")
        os.makedirs(os.path.dirname(old))
        with open(old, "wb") as f:
            f.write(PNG)
        results.write_pending(self.path, "toy", "Toy study", "snakemake -s experiments/toy/Snakefile --cores 2",
                              "about 3 h of CPU", [old])
        with open(self.path, encoding="utf-8") as f:
            text = f.read()
        self.assertIn("about 3 h of CPU", text)
        self.assertIn("```\nsnakemake -s experiments/toy/Snakefile --cores 2\n```", text)
        self.assertIn("![old.png](figures/old.png)", text)
        self.assertIn("What the toy study measures.", text)
        entry = results.read_index_entry(self.path)
        self.assertTrue(entry["pending"])
        self.assertEqual(entry["headline"], "not yet run at this revision")


if __name__ == "__main__":
    unittest.main()
