"""A study's RESULTS.md, written by the last rule of its workflow
(experiments/<study>/Snakefile) from the outputs, never by hand.

A RESULTS.md holds, in this order: a metadata comment the index reads
(`study_index.py`), the title, the provenance (revision, machine, date, the
Snakemake command line), the study's own description (`about.md` beside its
Snakefile: what it measures and how to read it, with no measured numbers),
one section per table or figure, each cell's wall and CPU time (Snakemake's
`benchmark:` files) and the exact command of every cell.

In a Snakefile:

    sys.path.insert(0, "experiments/common")
    from results import Table, Figure, write_results

    rule results:
        input: f"{OUT}/drape.csv", f"{OUT}/drape.png"
        output: RESULTS
        run:
            write_results(output[0], study="cusick", title="Cusick drape",
                          sections=[Table("Drape coefficient per model", input[0]),
                                    Figure("Drape from above", input[1])],
                          commands=COMMANDS, benchmarks=BENCHMARKS,
                          headline=Headline("drape coefficient {value} (yarn, 65×65)", input[0],
                                            column="drape_coefficient", where={"model": "yarn"}))

Figures are copied into `figures/` beside RESULTS.md so that the Markdown
shows them wherever the repository is read.
"""
import csv
import dataclasses
import datetime
import json
import os
import platform
import shutil
import subprocess
import sys

MARKER = "<!-- weavelab-study "


@dataclasses.dataclass
class Table:
    """A CSV file shown as a Markdown table. `columns` picks and orders the
    columns (default: all); `digits` is the number of significant digits of
    floating-point cells."""
    title: str
    path: str
    columns: list = None
    caption: str = ""
    digits: int = 4


@dataclasses.dataclass
class Figure:
    """A picture (PNG or SVG) shown with a caption."""
    title: str
    path: str
    caption: str = ""


@dataclasses.dataclass
class Text:
    """A generated text file (Markdown) included as it is: a verdict or a
    summary a script of the study wrote from the outputs."""
    title: str
    path: str


@dataclasses.dataclass
class Headline:
    """The study's one line in the index: `text` with `{value}` replaced by
    one cell of a CSV file, the row chosen by `where` (column -> value)."""
    text: str
    path: str
    column: str
    where: dict = dataclasses.field(default_factory=dict)
    digits: int = 3


def format_cell(text, digits):
    """A CSV cell as shown: floats to `digits` significant digits, the rest as it is."""
    try:
        value = float(text)
    except ValueError:
        return text.replace("|", "\\|")
    if text.strip().lstrip("-").isdigit():
        return text.strip()
    return f"{value:.{digits}g}"


def read_csv(path):
    with open(path, newline="", encoding="utf-8") as f:
        return list(csv.DictReader(f))


def markdown_table(table):
    rows = read_csv(table.path)
    if not rows:
        return "(no rows)\n"
    columns = table.columns or list(rows[0].keys())
    missing = [c for c in columns if c not in rows[0]]
    if missing:
        raise ValueError(f"{table.path}: no column {', '.join(missing)} (has {', '.join(rows[0].keys())})")
    lines = ["| " + " | ".join(columns) + " |", "|" + "---|" * len(columns)]
    for row in rows:
        lines.append("| " + " | ".join(format_cell(row[c] or "", table.digits) for c in columns) + " |")
    return "\n".join(lines) + "\n"


def headline_value(headline):
    for row in read_csv(headline.path):
        if all(str(row.get(k)) == str(v) for k, v in headline.where.items()):
            return format_cell(row[headline.column], headline.digits)
    raise ValueError(f"{headline.path}: no row with {headline.where}")


def git(*args):
    try:
        return subprocess.run(["git", *args], capture_output=True, text=True, check=True).stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        return "unknown"


def machine():
    """Cores, memory, processor and the load averages (1, 5, 15 min) now."""
    cpu = platform.processor() or platform.machine()
    try:
        with open("/proc/cpuinfo", encoding="utf-8") as f:
            names = [line.split(":", 1)[1].strip() for line in f if line.startswith("model name")]
        cpu = names[0] if names else cpu
    except OSError:
        pass
    memory_gb = os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES") / 2**30
    load = ", ".join(f"{x:.2f}" for x in os.getloadavg())
    return f"{os.cpu_count()} cores ({cpu}), {memory_gb:.0f} GiB, load average {load} (1, 5, 15 min) when written"


# The command line the user typed. Snakemake runs a `run:` block in a process
# of its own whose arguments are internal; this module is first imported while
# the user's snakemake reads the Snakefile, so the command is kept in the
# environment then, which the job processes inherit.
COMMAND_VARIABLE = "WEAVELAB_WORKFLOW_COMMAND"
os.environ.setdefault(COMMAND_VARIABLE, " ".join([os.path.basename(sys.argv[0]), *sys.argv[1:]]) if sys.argv else "")


def provenance():
    return {
        "revision": git("describe", "--always", "--dirty", "--abbrev=12"),
        "date": datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC"),
        "machine": machine(),
        "command": os.environ[COMMAND_VARIABLE],
    }


def benchmark_table(paths):
    """Each cell's wall time, CPU time and peak memory from Snakemake's benchmark files."""
    lines = ["| cell | wall [s] | CPU [s] | peak RSS [MB] |", "|---|---|---|---|"]
    for path in sorted(paths):
        rows = []
        with open(path, encoding="utf-8") as f:
            rows = list(csv.DictReader(f, delimiter="\t"))
        if rows:
            row = rows[0]
            lines.append(f"| {path} | {format_cell(row['s'], 4)} | {format_cell(row.get('cpu_time', 'NA'), 4)} "
                         f"| {format_cell(row.get('max_rss', 'NA'), 4)} |")
    return "\n".join(lines) + "\n"


def write_results(path, study, title, sections, commands, benchmarks=(), headline=None, about=None):
    """Writes RESULTS.md at `path` (under a temporary name, then renamed).
    `about` defaults to about.md beside `path`."""
    folder = os.path.dirname(os.path.abspath(path))
    about = about or os.path.join(folder, "about.md")
    meta = provenance()
    figures = os.path.join(folder, "figures")
    index = {"study": study, "title": title, "revision": meta["revision"], "date": meta["date"],
             "headline": None, "figure": None}
    out = [f"# {title}\n",
           "Written by this study's workflow from its outputs: do not edit; rerun it instead.\n",
           f"- revision: `{meta['revision']}`", f"- date: {meta['date']}", f"- machine: {meta['machine']}",
           f"- workflow command: `{meta['command']}`", ""]
    if headline:
        index["headline"] = headline.text.replace("{value}", headline_value(headline))
        out += [f"**{index['headline']}**", ""]
    if os.path.isfile(about):
        with open(about, encoding="utf-8") as f:
            out += [f.read().strip(), ""]
    for section in sections:
        anchor = section.title
        out.append(f"## {anchor}\n")
        if isinstance(section, Table):
            out.append(markdown_table(section))
        elif isinstance(section, Figure):
            os.makedirs(figures, exist_ok=True)
            name = os.path.basename(section.path)
            shutil.copyfile(section.path, os.path.join(figures, name))
            index["figure"] = index["figure"] or f"figures/{name}"
            out.append(f"![{section.title}](figures/{name})\n")
        elif isinstance(section, Text):
            with open(section.path, encoding="utf-8") as f:
                out.append(f.read().strip() + "\n")
        if getattr(section, "caption", ""):
            out.append(section.caption + "\n")
    if benchmarks:
        out += ["## Cost of each cell\n", benchmark_table(benchmarks)]
    out += ["## Commands\n", "Each cell, as the workflow ran it (from the repository root):\n", "```"]
    out += list(commands) + ["```", ""]
    text = MARKER + json.dumps(index, ensure_ascii=False) + " -->\n" + "\n".join(out)
    with open(path + ".tmp", "w", encoding="utf-8") as f:
        f.write(text)
    os.replace(path + ".tmp", path)


def read_index_entry(results_path):
    """The metadata a RESULTS.md carries for the index, or None when the file has none."""
    with open(results_path, encoding="utf-8") as f:
        first = f.readline()
    if not first.startswith(MARKER):
        return None
    return json.loads(first[len(MARKER):].rsplit("-->", 1)[0])


def write_pending(path, study, title, command, reason, earlier_figures=()):
    """Writes a RESULTS.md that says the study has not been run at this
    revision, why (e.g. its cost), and the one command that runs it. Figures
    left from an earlier revision are shown with that revision named, so that
    nothing passes for a result of this one."""
    folder = os.path.dirname(os.path.abspath(path))
    meta = provenance()
    index = {"study": study, "title": title, "revision": meta["revision"], "date": meta["date"],
             "headline": "not yet run at this revision", "figure": None, "pending": True}
    out = [f"# {title}\n",
           "Written by this study's workflow: do not edit; rerun it instead.\n",
           f"**Not yet run at revision `{meta['revision']}`** ({meta['date']}): {reason}\n",
           "Run it from the repository root with:\n", "```", command, "```", ""]
    about = os.path.join(folder, "about.md")
    if os.path.isfile(about):
        with open(about, encoding="utf-8") as f:
            out += [f.read().strip(), ""]
    for figure in earlier_figures:
        # the last commit that changed the picture, not one that only moved it
        revision = git("log", "-1", "--follow", "--diff-filter=AM", "--format=%h", "--", figure) or "unknown"
        out.append(f"![{os.path.basename(figure)}]({os.path.relpath(figure, folder)})\n")
        out.append(f"Figure from revision `{revision}`, before this study became a workflow.\n")
    text = MARKER + json.dumps(index, ensure_ascii=False) + " -->\n" + "\n".join(out)
    with open(path + ".tmp", "w", encoding="utf-8") as f:
        f.write(text)
    os.replace(path + ".tmp", path)


if __name__ == "__main__":
    import argparse

    parser = argparse.ArgumentParser(description="Write a study's RESULTS.md that says it is not yet run at this revision.")
    parser.add_argument("results", help="experiments/<study>/RESULTS.md")
    parser.add_argument("--study", required=True)
    parser.add_argument("--title", required=True)
    parser.add_argument("--command", required=True, help="the command that runs the study")
    parser.add_argument("--reason", required=True, help="why it was not run (e.g. its cost)")
    parser.add_argument("--figure", action="append", default=[], help="a figure of an earlier revision")
    args = parser.parse_args()
    write_pending(args.results, args.study, args.title, args.command, args.reason, args.figure)
