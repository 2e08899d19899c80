#!/usr/bin/python3
"""The index of the studies (experiments/INDEX.md), generated from the
metadata each study's RESULTS.md carries (results.py, read_index_entry): per
study one line, its title, headline, one figure, a link to its RESULTS.md and
the revision and date it was written at. A study whose RESULTS.md is missing,
or says it was not run at its revision, is marked as not yet run.

The same table, with paths relative to the repository root, replaces the block
between `<!-- results-index:start -->` and `<!-- results-index:end -->` of the
README given with --readme, when the README has both markers (else it is left
alone).

Usage: study_index.py INDEX RESULTS_MD... [--readme README.md]
Each RESULTS_MD is experiments/<study>/RESULTS.md; the study is its folder's name.
"""
import argparse
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from results import read_index_entry  # noqa: E402

START, END = "<!-- results-index:start -->", "<!-- results-index:end -->"


def fail(message):
    print(f"study_index.py: error: {message}", file=sys.stderr)
    sys.exit(2)


def read_entry(results_path):
    """The study's index entry; missing or pending studies get pending=True."""
    study = os.path.basename(os.path.dirname(os.path.abspath(results_path)))
    if not os.path.isfile(results_path):
        return {"study": study, "title": study, "pending": True, "revision": None, "date": None,
                "headline": "not yet run", "figure": None, "path": results_path, "exists": False}
    try:
        entry = read_index_entry(results_path)
    except ValueError as e:
        fail(f"{results_path}: line 1: the metadata comment is not valid JSON ({e})")
    if entry is None:
        fail(f"{results_path}: line 1: expected the metadata comment '<!-- weavelab-study {{...}} -->' "
             "that results.py writes")
    for key in ("study", "title"):
        if key not in entry:
            fail(f"{results_path}: line 1: the metadata has no key '{key}'")
    entry.setdefault("pending", False)
    entry.update(path=results_path, exists=True)
    return entry


def link(target, base):
    """`target` relative to the folder `base`, with forward slashes."""
    return os.path.relpath(os.path.abspath(target), os.path.abspath(base)).replace(os.sep, "/")


def table(entries, base):
    """The Markdown table of the entries, paths relative to the folder `base`."""
    lines = ["| study | result | figure | revision, date |", "|---|---|---|---|"]
    for e in entries:
        title = e["title"].replace("|", "\\|")
        name = f"[{title}]({link(e['path'], base)})" if e["exists"] else title
        if e["pending"]:
            headline = f"*{e.get('headline') or 'not yet run'}*"
        else:
            headline = (e.get("headline") or "").replace("|", "\\|")
        figure = ""
        if e.get("figure"):
            picture = os.path.join(os.path.dirname(e["path"]), e["figure"])
            figure = f'<img src="{link(picture, base)}" width="240" alt="{title}">'
        when = f"`{e['revision']}`, {e['date']}" if e.get("revision") else ""
        lines.append(f"| {name} | {headline} | {figure} | {when} |")
    return "\n".join(lines) + "\n"


def write_atomically(path, text):
    with open(path + ".tmp", "w", encoding="utf-8") as f:
        f.write(text)
    os.replace(path + ".tmp", path)


def write_index(index_path, entries):
    base = os.path.dirname(os.path.abspath(index_path))
    text = ("# Studies\n\n"
            "Generated from each study's RESULTS.md by `snakemake --cores 1 index` (from the repository root): "
            "do not edit. How to run a study: [README.md](README.md).\n\n" + table(entries, base))
    write_atomically(index_path, text)


def readme_with_index(readme_path, entries):
    """The README's text with the block between the markers replaced; None when it has no markers."""
    with open(readme_path, encoding="utf-8") as f:
        text = f.read()
    start, end = text.find(START), text.find(END)
    if start < 0 and end < 0:
        return None
    if start < 0 or end < start:
        fail(f"{readme_path}: expected '{START}' before '{END}'")
    block = START + "\n" + table(entries, os.path.dirname(os.path.abspath(readme_path))) + END
    return text[:start] + block + text[end + len(END):]


def main(argv=None):
    parser = argparse.ArgumentParser(description="Write the index of the studies from their RESULTS.md.")
    parser.add_argument("index", help="the index to write (experiments/INDEX.md)")
    parser.add_argument("results", nargs="+", help="experiments/<study>/RESULTS.md, in the order listed")
    parser.add_argument("--readme", help="a README whose results-index block is rewritten")
    args = parser.parse_args(argv)
    entries = [read_entry(p) for p in args.results]
    if args.readme and not os.path.isfile(args.readme):
        fail(f"--readme: no file '{args.readme}'")
    readme = readme_with_index(args.readme, entries) if args.readme else None  # checked before writing
    write_index(args.index, entries)
    if readme is not None:
        write_atomically(args.readme, readme)


if __name__ == "__main__":
    main()
