#!/usr/bin/python3
"""The speed table in one run: per row the median over REPEATS runs of the
backward-Euler step (be-linear, from the run summary's statistics: wall and
process CPU time, user + system, over the steps only) or of the calibration fit
(calibration.json: fit_wall_s, fit_cpu_s), for this build, for a reference
build when one is given, and for this build on one thread. The runs of a repeat
are interleaved (this, reference, one thread; row after row), so load from
other processes falls on all of them alike.

    experiments/speed/scripts/speed_table.py [ROW ...] [--weavelab PROGRAM] [--reference PROGRAM]
        [--repeats 3] [--calibration-starts 4] [--csv OUT.csv] [--markdown OUT.md]

Rows: yarn-17, fem-17, yarn-65, fem-65, fem-65-stride2 (the default), and on
request calibrate (a fit takes minutes per run) and yarn-257 (10 steps of
328 197 DoFs, about 4 GB per run). Each run's peak resident memory is reported
beside its step. The Markdown table and the ratios between rows go to stdout
(and --markdown); --csv has one row per table row and build.
"One thread" is OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 OMP_THREAD_LIMIT=1: the
thread limit holds CHOLMOD too, whose parallel loops name their own thread count.
"""
import argparse
import csv
import io
import json
import os
import shutil
import statistics
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))
SCENES = os.path.join(ROOT, "experiments", "scenes")
ONE_THREAD = {"OMP_NUM_THREADS": "1", "OPENBLAS_NUM_THREADS": "1", "OMP_THREAD_LIMIT": "1"}


def fail(message, code=2):
    print(f"speed_table: {message}", file=sys.stderr)
    sys.exit(code)


def stride2_scene(tmp):
    """hanging_wind_65.toml with [fem] stride = 2 (the scene has no [fem] table)."""
    with open(os.path.join(SCENES, "hanging_wind_65.toml")) as f:
        text = f.read()
    if "\n[fem]" in text:
        fail("hanging_wind_65.toml has a [fem] table now: set its stride here", 1)
    path = os.path.join(tmp, "hanging_wind_65_stride2.toml")
    with open(path, "w") as f:
        f.write(text + "\n[fem]\nstride = 2\n")
    return path


# name: (label, scene, model, duration [s]); calibrate is separate.
def run_rows(tmp):
    return {
        "yarn-17": ("yarn 17×17", os.path.join(SCENES, "hanging_wind.toml"), "yarn", 0.1),
        "fem-17": ("FEM 17×17", os.path.join(SCENES, "hanging_wind.toml"), "fem", 0.1),
        "yarn-65": ("yarn 65×65", os.path.join(SCENES, "hanging_wind_65.toml"), "yarn", 0.004),
        "fem-65": ("FEM 65×65", os.path.join(SCENES, "hanging_wind_65.toml"), "fem", 0.01),
        "fem-65-stride2": ("FEM 65×65 stride 2", stride2_scene(tmp), "fem", 0.04),
        "yarn-257": ("yarn 257×257", os.path.join(SCENES, "hanging_wind_257.toml"), "yarn", 0.01),
    }


ON_REQUEST = {"calibrate", "yarn-257"}


def measure(binary, row, env_extra, tmp, starts):
    """One run: (wall, cpu) per step [ms] (calibrate: the fit [s]) and facts."""
    out = tempfile.mkdtemp(dir=tmp)
    env = dict(os.environ, **env_extra)
    if row[0] == "calibrate":
        cmd = [binary, "calibrate", os.path.join(SCENES, "hanging_wind.toml"), "--starts", str(starts), "--out", out]
    else:
        _, scene, model, duration = row[1]
        # One frame at the end: older builds refuse a duration below the scene's frame interval.
        cmd = [binary, "run", scene, "--model", model, "--integrator", "be-linear", "--duration", str(duration),
               "--output-interval", str(duration), "--out", out, "--quiet"]
    p = subprocess.run(cmd, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    if p.returncode != 0:
        fail(f"{' '.join(cmd)} exited {p.returncode}: {p.stderr.strip()[-400:]}", 1)
    if row[0] == "calibrate":
        with open(os.path.join(out, "calibration.json")) as f:
            j = json.load(f)
        t = j["timings"]
        facts = {"evaluations": j["fit"]["curve_evaluations"], "cost": j["fit"]["cost"]}
        result = (t["fit_wall_s"], t["fit_cpu_s"], facts)
    else:
        with open(os.path.join(out, "summary.json")) as f:
            j = json.load(f)
        s = j["statistics"]
        n = s["steps"]
        facts = {"dofs": int(j["model"]["dofs"]), "fact": s["factorizations"] / n, "krylov": s["krylov_iters"] / n,
                 "peak_gb": j.get("memory", {}).get("peak_resident_bytes", float("nan")) / 1e9}
        result = (1e3 * s["wall_s"] / n, 1e3 * s["cpu_s"] / n, facts)
    shutil.rmtree(out, ignore_errors=True)
    return result


def parse_args():
    parser = argparse.ArgumentParser(description="The speed table: medians of interleaved runs.")
    parser.add_argument("rows", nargs="*", help="rows (default: every row but calibrate and yarn-257)")
    parser.add_argument("--weavelab", default=os.path.join(ROOT, "build", "weavelab"), help="this build")
    parser.add_argument("--reference", default="", help="a reference build to compare with (default none)")
    parser.add_argument("--repeats", type=int, default=3, help="runs per row and build")
    parser.add_argument("--calibration-starts", type=int, default=4, help="starts of the calibration row")
    parser.add_argument("--csv", help="write the medians here, one row per table row and build")
    parser.add_argument("--markdown", help="write the tables here too")
    args = parser.parse_args()
    for name in ("repeats", "calibration_starts"):
        if getattr(args, name) < 1:
            fail(f"--{name.replace('_', '-')}: got {getattr(args, name)}, expected a positive integer")
    return args


def main():
    args = parse_args()
    binary, reference, repeats, starts = args.weavelab, args.reference, args.repeats, args.calibration_starts
    for b in [binary] + ([reference] if reference else []):
        if not (os.path.isfile(b) and os.access(b, os.X_OK)):
            fail(f"no executable program at '{b}'")
    tmp = tempfile.mkdtemp(prefix="speed_table_")
    try:
        rows = run_rows(tmp)
        names = args.rows or [n for n in rows if n not in ON_REQUEST]
        for n in names:
            if n not in rows and n != "calibrate":
                fail(f"unknown row '{n}', expected one of {', '.join(list(rows) + ['calibrate'])}")
        builds = [("this", binary, {})] + ([("reference", reference, {})] if reference else [])
        builds.append(("one thread", binary, ONE_THREAD))
        samples = {(n, b[0]): [] for n in names for b in builds}
        for r in range(repeats):
            for n in names:
                row = (n, rows.get(n))
                for label, b, env in builds:
                    samples[(n, label)].append(measure(b, row, env, tmp, starts))
                    w, c, _ = samples[(n, label)][-1]
                    print(f"repeat {r + 1}/{repeats} {n:15s} {label:10s} wall {w:9.3f} cpu {c:9.3f}", file=sys.stderr,
                          flush=True)
        text = io.StringIO()
        report(names, rows, builds, samples, binary, reference, repeats, starts, text)
        print(text.getvalue(), end="")
        if args.markdown:
            write_atomically(args.markdown, text.getvalue())
        if args.csv:
            write_csv(args.csv, names, rows, builds, samples, starts)
    finally:
        shutil.rmtree(tmp, ignore_errors=True)


def write_atomically(path, text):
    with open(path + ".tmp", "w", encoding="utf-8") as f:
        f.write(text)
    os.replace(path + ".tmp", path)


def write_csv(path, names, rows, builds, samples, starts):
    """One line per row and build: medians of wall and CPU (ms per step; calibrate: s per fit)."""
    out = io.StringIO()
    w = csv.writer(out, lineterminator="\n")
    w.writerow(["row", "label", "build", "unit", "dofs", "wall", "cpu", "factorizations_per_step",
                "gmres_iterations_per_step", "peak_gb", "repeats"])
    for n in names:
        for label, _, _ in builds:
            s = samples[(n, label)]
            facts = s[0][2]
            w.writerow([n, f"calibrate, {starts} starts (fit)" if n == "calibrate" else rows[n][0], label,
                        "s per fit" if n == "calibrate" else "ms per step", facts.get("dofs", ""),
                        f"{statistics.median(x[0] for x in s):.4g}", f"{statistics.median(x[1] for x in s):.4g}",
                        f"{facts['fact']:.3f}" if "fact" in facts else "",
                        f"{facts['krylov']:.2f}" if "krylov" in facts else "",
                        f"{statistics.median(x[2]['peak_gb'] for x in s):.3f}" if "peak_gb" in facts else "",
                        len(s)])
    write_atomically(path, out.getvalue())


def report(names, rows, builds, samples, binary, reference, repeats, starts, out):
    med = {k: (statistics.median(s[0] for s in v), statistics.median(s[1] for s in v)) for k, v in samples.items()}
    print(f"this build: {binary}; reference: {reference or 'none'}; medians of {repeats} interleaved runs;", file=out)
    print("per be-linear step in ms (calibrate: the fit in s); wall / CPU (user + system)", file=out)
    print(file=out)
    head = "| row | DoFs | this: wall / CPU | factorizations, GMRES its per step | peak memory [GB]"
    head += ": this / reference |" if reference else " |"
    if reference:
        head += " reference: wall / CPU | speed-up vs reference: wall / CPU |"
    head += " this, one thread: wall / CPU |"
    print(head, file=out)
    print("|" + "---|" * (head.count("|") - 1), file=out)
    for n in names:
        w, c = med[(n, "this")]
        facts = samples[(n, "this")][0][2]
        label = f"calibrate, {starts} starts (fit)" if n == "calibrate" else rows[n][0]
        dofs = str(facts["dofs"]) if "dofs" in facts else "–"
        solver = f"{facts['fact']:.2f}, {facts['krylov']:.1f}" if "fact" in facts else f"{facts['evaluations']} evaluations"
        peak = " / ".join(f"{statistics.median(x[2]['peak_gb'] for x in samples[(n, b)]):.2f}"
                          for b in ["this"] + (["reference"] if reference else [])) if "peak_gb" in facts else "–"
        line = f"| {label} | {dofs} | {w:.3f} / {c:.3f} | {solver} | {peak} |"
        if reference:
            rw, rc = med[(n, "reference")]
            line += f" {rw:.3f} / {rc:.3f} | {rw / w:.2f} / {rc / c:.2f} |"
        ow, oc = med[(n, "one thread")]
        line += f" {ow:.3f} / {oc:.3f} |"
        print(line, file=out)
    # Ratios between rows of one build (from the medians above).
    pairs = [("yarn-65", "fem-65"), ("yarn-65", "fem-65-stride2"), ("yarn-17", "fem-17")]
    pairs = [p for p in pairs if p[0] in names and p[1] in names]
    if pairs:
        print(file=out)
        print("| ratio of steps | this: wall / CPU |" + (" reference: wall / CPU |" if reference else ""), file=out)
        print("|---|---|" + ("---|" if reference else ""), file=out)
        for a, b in pairs:
            line = f"| {rows[a][0]} / {rows[b][0]} |"
            for label in ["this"] + (["reference"] if reference else []):
                line += f" {med[(a, label)][0] / med[(b, label)][0]:.2f} / {med[(a, label)][1] / med[(b, label)][1]:.2f} |"
            print(line, file=out)


if __name__ == "__main__":
    main()
