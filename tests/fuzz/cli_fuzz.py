#!/usr/bin/env python3
"""Seeded fuzz of the command line: every subcommand of `weavelab` on mutated input.

Each case takes one small valid input — a scene (woven, continuum, knit, obstacles), a
continuum parameter file, the target run of `fit` or the reference of `fidelity
--reference-from` — applies one to three random mutations (a key deleted, a value
replaced by NaN, ±inf, a huge, negative or zero number or a value of the wrong type,
a table duplicated, the file truncated, bytes of binary garbage; for run folders a
header count made huge, a coordinate NaN, frame times out of order, a frame that
names /dev/zero) and, now and then, one numeric option replaced the same way, then
runs one subcommand on it, round robin over all eleven. A case passes when the process
ends within its time limit, with exit 0, 1 or 2 (3, output that could not be written,
cannot happen in a fresh folder), no sanitizer report and no std::bad_alloc, and an
exit 2 left nothing in its --out folder.

    tests/fuzz/cli_fuzz.py --weavelab build/weavelab --cases 10000 --jobs 2

runs a longer campaign; ctest runs a fixed, seeded number of cases (CMakeLists.txt,
fuzz.cli). A failing case is kept (--keep DIR) with the command to run it again.
"""
import argparse
import os
import random
import re
import shutil
import subprocess
import sys
import tempfile
import time
from concurrent.futures import ThreadPoolExecutor

# ---- the valid inputs (tests/fuzz/inputs/, shared with input_fuzz_test.cpp) -----------------

INPUTS = os.path.join(os.path.dirname(os.path.abspath(__file__)), "inputs")


def read_input(name):
    with open(os.path.join(INPUTS, name)) as f:
        return f.read()


SCENES = {name: read_input(name + ".toml") for name in ("woven", "flat", "continuum", "knit", "obstacles")}
# The knit without yarn viscosity, which a knit's continuum refuses (for the commands that run both).
SCENES["knit_undamped"] = SCENES["knit"].replace("[damping]\nyarn_viscosity_Pa_s = 10.0\n", "")
assert SCENES["knit_undamped"] != SCENES["knit"]
PARAMS = read_input("params.toml")

# ---- mutations -------------------------------------------------------------------------

VALUES = ["nan", "inf", "-inf", "0", "0.0", "-1", "-0.5", "1", "1e-300", "1e30", "1e300", "-1e300",
          "9223372036854775807", "-9223372036854775808", "18446744073709551616", "\"text\"", "\"\"", "true",
          "[1, 2]", "[]", "{}", "[nan, nan, nan]", "[1e308, -1e308, 0]", "1979-05-27", "\"/dev/zero\""]
OPTION_VALUES = ["nan", "inf", "-inf", "0", "-1", "1e300", "1e-300", "x", "9223372036854775807", ""]


def garbage(rng, n):
    return bytes(rng.randrange(256) for _ in range(n))


def cut_or_garble(data, kind, rng):
    """`data` cut at a random byte ("truncate") or with garbage inserted ("garbage"), else as it is."""
    if kind == "truncate":
        return data[:rng.randrange(len(data) + 1)]
    if kind == "garbage":
        at = rng.randrange(len(data) + 1)
        return data[:at] + garbage(rng, rng.randrange(1, 64)) + data[at:]
    return data


def mutate_lines(text, rng):
    """One mutation of a TOML text (bytes out: it may hold garbage)."""
    lines = text.split("\n")
    assignments = [k for k, l in enumerate(lines) if " = " in l]
    headers = [k for k, l in enumerate(lines) if l.startswith("[")]
    # Mostly one key's value or presence (what the readers check one by one); now and then the file's form.
    kind = rng.choices(["delete", "replace", "truncate", "duplicate_table", "duplicate_key", "garbage", "flip", "swap"],
                       weights=[3, 10, 1, 1, 1, 1, 1, 1])[0]
    if kind == "delete" and assignments:
        del lines[rng.choice(assignments)]
    elif kind == "replace" and assignments:
        k = rng.choice(assignments)
        lines[k] = lines[k].split(" = ")[0] + " = " + rng.choice(VALUES)
    elif kind == "duplicate_table" and headers:
        start = rng.choice(headers)
        end = next((k for k in headers if k > start), len(lines))
        lines += lines[start:end]
    elif kind == "duplicate_key" and assignments:
        k = rng.choice(assignments)
        lines.insert(k, lines[k])
    elif kind == "swap" and len(lines) > 2:
        a, b = rng.randrange(len(lines)), rng.randrange(len(lines))
        lines[a], lines[b] = lines[b], lines[a]
    data = cut_or_garble("\n".join(lines).encode("utf-8", "surrogateescape"), kind, rng)
    if kind == "flip" and data:
        b = bytearray(data)
        for _ in range(rng.randrange(1, 8)):
            b[rng.randrange(len(b))] = rng.randrange(256)
        data = bytes(b)
    return data


def mutate_text(text, rng):
    data = text.encode()
    for _ in range(rng.choice([1, 1, 1, 2, 3])):
        data = mutate_lines(data.decode("utf-8", "surrogateescape"), rng)
    return data.decode("utf-8", "surrogateescape").encode("utf-8", "surrogateescape")


def mutate_vtu(data, rng):
    """One mutation of a VTU frame: a header count, a coordinate, the file's end, garbage."""
    text = data.decode("utf-8", "surrogateescape")
    kind = rng.choice(["count", "count", "coordinate", "coordinate", "truncate", "garbage", "components"])
    if kind == "count":
        huge = rng.choice(["2000000000", "9223372036854775808", "-1", "0", "1", "nan", "1e300", "4294967296"])
        text = re.sub(r'Number(OfPoints|OfCells)="\d+"', lambda m: 'Number%s="%s"' % (m.group(1), huge), text,
                      count=1)
    elif kind == "coordinate":
        numbers = list(re.finditer(r"-?\d+\.?\d*(e[-+]?\d+)?", text))
        if numbers:
            m = rng.choice(numbers)
            text = text[:m.start()] + rng.choice(["nan", "inf", "-inf", "1e308", "x", ""]) + text[m.end():]
    elif kind == "components":
        text = text.replace('NumberOfComponents="3"', 'NumberOfComponents="%s"' % rng.choice(["0", "2", "-3", "1e9"]),
                            1)
    return cut_or_garble(text.encode("utf-8", "surrogateescape"), kind, rng)


def mutate_pvd(data, rng):
    """One mutation of run.pvd: times out of order or not numbers, a frame named /dev/zero, a frame
    missing or repeated, the file cut."""
    text = data.decode("utf-8", "surrogateescape")
    times = list(re.finditer(r'timestep="([^"]*)"', text))
    kind = rng.choice(["order", "time", "devzero", "missing", "repeat", "truncate", "garbage"])
    if kind == "order" and len(times) > 1:
        a, b = rng.sample(range(len(times)), 2)
        ta, tb = times[a].group(1), times[b].group(1)
        text = re.sub(r'timestep="[^"]*"', lambda m, it=iter(range(len(times))): (
            lambda k: 'timestep="%s"' % (tb if k == a else ta if k == b else times[k].group(1)))(next(it)), text)
    elif kind == "time" and times:
        m = rng.choice(times)
        text = text[:m.start(1)] + rng.choice(["nan", "inf", "-1", "1e300", "x", ""]) + text[m.end(1):]
    elif kind == "devzero":
        files = list(re.finditer(r'file="([^"]*)"', text))
        if files:
            m = rng.choice(files)
            text = text[:m.start(1)] + rng.choice(["/dev/zero", "/dev/null", "/", "frames", "../run.pvd",
                                                   "missing.vtu"]) + text[m.end(1):]
    elif kind in ("missing", "repeat"):
        sets = list(re.finditer(r"<DataSet[^>]*/>\n?", text))
        if sets:
            m = rng.choice(sets)
            text = text[:m.start()] + ("" if kind == "missing" else m.group(0) * 2) + text[m.end():]
    return cut_or_garble(text.encode("utf-8", "surrogateescape"), kind, rng)


def mutate_binary(data, rng):
    """One mutation of reference.bin: bytes flipped, a count made huge, the file cut or extended."""
    b = bytearray(data)
    kind = rng.choice(["flip", "count", "truncate", "extend", "nan"])
    if kind == "flip" and b:
        for _ in range(rng.randrange(1, 16)):
            b[rng.randrange(len(b))] = rng.randrange(256)
    elif kind == "count" and len(b) > 16:
        at = rng.randrange(8, len(b) - 8)
        b[at:at + 8] = rng.choice([b"\xff" * 8, b"\x00\x00\x00\x80\x00\x00\x00\x00", b"\xff\xff\xff\x7f\x00\x00\x00\x00"])
    elif kind == "truncate":
        del b[rng.randrange(len(b) + 1):]
    elif kind == "extend":
        b += garbage(rng, rng.randrange(1, 256))
    elif kind == "nan" and len(b) > 16:
        at = rng.randrange(8, len(b) - 8)
        b[at:at + 8] = b"\x00\x00\x00\x00\x00\x00\xf8\x7f"
    return bytes(b)


# ---- the subcommands -------------------------------------------------------------------

# Per subcommand: the scenes it takes, its options (small and quick), and which of its
# numeric options a case may spoil.
COMMANDS = {
    "run": (["woven", "continuum", "knit", "obstacles", "flat"], ["--duration", "0.004", "--quiet"],
            ["--duration", "--dt", "--rtol"]),
    "info": (["woven", "continuum", "knit", "obstacles", "flat"], [], []),
    "diagnose": (["woven", "knit", "flat"], ["--duration", "0.004", "--no-error-estimate", "--quiet"],
                 ["--duration", "--rtol"]),
    # not the flat cloth: its equilibrium hanging from one pin takes seconds to find
    "modes": (["woven", "knit_undamped"], ["--count", "2", "--quiet"], ["--count", "--lean"]),
    "fidelity": (["woven", "flat"], ["--duration", "0.004", "--no-error-estimate", "--quiet", "--time-steps", "scene",
                                     "--variants", "full,frozen_sliding"], ["--duration", "--tolerance", "--repeats"]),
    "fit": (["woven"], ["--free", "contact.shear_modulus_Pa", "--frames", "1", "--max-iterations", "1", "--quiet"],
            ["--frames", "--max-iterations", "--bound-factor"]),
    "calibrate": (["flat", "knit"], ["--tests", "uniaxial-warp", "--starts", "1", "--quiet"],
                  ["--patch", "--starts", "--seed"]),
    "stability": (["woven", "continuum", "flat"], ["--duration", "0.004", "--bisections", "1", "--multipliers", "1",
                                                   "--integrators", "be-linear", "--dt-min", "0.0005", "--dt-max",
                                                   "0.001", "--quiet"],
                  ["--duration", "--bisections", "--dt-min", "--dt-max", "--speed-bound"]),
    "work-precision": (["woven", "flat"], ["--duration", "0.002", "--integrators", "be-linear", "--dt-max", "0.002",
                                           "--dt-min", "0.001", "--reference-rtols", "1e-5", "--quiet"],
                       ["--duration", "--dt-max", "--dt-min", "--budget"]),
    "pull": (["flat", "knit"], ["--strains", "0.01"], ["--strains"]),
    "tiles": (["woven", "flat"], ["--samples", "4", "--no-fit"], ["--samples", "--seed", "--holdout-every"]),
}
# The continuum scene is run as the continuum (the experiments take a list of models).
MODEL_OPTION = {"continuum": ["--model", "fem"]}
MODELS_OPTION = {"continuum": ["--models", "fem"]}
WRITES_NOTHING = {"info"}


class Bases:
    """The valid inputs on disk, and the run and reference made from them once."""

    def __init__(self, weavelab, root, timeout):
        self.root = root
        self.scenes = {}
        for name, text in SCENES.items():
            path = os.path.join(root, name + ".toml")
            with open(path, "w") as f:
                f.write(text)
            self.scenes[name] = path
        self.params = os.path.join(root, "params.toml")
        with open(self.params, "w") as f:
            f.write(PARAMS)
        for name, path in self.scenes.items():  # a base the parser refuses would test nothing
            done = subprocess.run([weavelab, "info", path] + MODEL_OPTION.get(name, []), capture_output=True,
                                  timeout=timeout)
            if done.returncode != 0:
                raise SystemExit("cli_fuzz: the base scene %s is refused:\n%s" % (name, done.stderr.decode()))
        self.target = os.path.join(root, "target")
        self.reference = os.path.join(root, "reference")
        for args in (["run", self.scenes["woven"], "--duration", "0.004", "--quiet", "--out", self.target],
                     ["fidelity", self.scenes["woven"], "--reference-only"] + COMMANDS["fidelity"][1][:-2] +
                     ["--out", self.reference]):
            done = subprocess.run([weavelab] + args, capture_output=True, timeout=timeout)
            if done.returncode != 0:
                raise SystemExit("cli_fuzz: the base input does not run: %s\n%s" % (" ".join(args), done.stderr.decode()))


def spoil_option(args, options, rng):
    option = rng.choice(options)
    value = rng.choice(OPTION_VALUES)
    if option in args:
        args[args.index(option) + 1] = value
    else:
        args += [option, value]


def make_case(index, rng, bases, workdir):
    """The argv of case `index` and a description of what was mutated."""
    command = list(COMMANDS)[index % len(COMMANDS)]
    scenes, options, spoilable = COMMANDS[command]
    scene_name = rng.choice(scenes)
    case_dir = os.path.join(workdir, "case%06d" % index)
    os.makedirs(case_dir)
    out = os.path.join(case_dir, "out")
    scene = os.path.join(case_dir, scene_name + ".toml")
    model = (MODELS_OPTION if command in ("stability", "work-precision") else MODEL_OPTION).get(scene_name, [])
    args = [command, scene] + model + list(options)
    what = scene_name
    choice = rng.random()
    scene_text = SCENES[scene_name].encode()
    if command == "fit" and choice < 0.5:
        target = os.path.join(case_dir, "target")
        shutil.copytree(bases.target, target)
        frames = sorted(os.listdir(os.path.join(target, "frames")))
        for _ in range(rng.choice([1, 1, 2])):
            if rng.random() < 0.4:
                path = os.path.join(target, "run.pvd")
                with open(path, "rb") as f:
                    data = mutate_pvd(f.read(), rng)
                what += " + run.pvd mutated"
            else:
                path = os.path.join(target, "frames", rng.choice(frames))
                with open(path, "rb") as f:
                    data = mutate_vtu(f.read(), rng)
                what += " + frame %s mutated" % os.path.basename(path)
            with open(path, "wb") as f:
                f.write(data)
        args += ["--target", target]
    elif command == "fidelity" and choice < 0.35:
        reference = os.path.join(case_dir, "reference")
        shutil.copytree(bases.reference, reference)
        path = os.path.join(reference, "reference.bin")
        with open(path, "rb") as f:
            data = mutate_binary(f.read(), rng)
        with open(path, "wb") as f:
            f.write(data)
        args += ["--reference-from", reference]
        what += " + reference.bin mutated"
    elif command in ("info", "diagnose", "modes", "fidelity") and choice < 0.3:
        params = os.path.join(case_dir, "params.toml")
        with open(params, "wb") as f:
            f.write(mutate_text(PARAMS, rng))
        args += ["--fem-params", params]
        what += " + parameter file mutated"
    else:
        scene_text = mutate_text(SCENES[scene_name], rng)
        what += " mutated"
    if command == "fit" and "--target" not in args:
        args += ["--target", bases.target]
    if command == "work-precision":
        args += ["--reference-dir", os.path.join(case_dir, "reference_cache")]
    if spoilable and rng.random() < 0.15:
        spoil_option(args, spoilable, rng)
        what += " + option spoilt"
    with open(scene, "wb") as f:
        f.write(scene_text)
    if command not in WRITES_NOTHING:
        args += ["--out", out]
    return args, what, case_dir, out


SANITIZER_REPORT = re.compile(r"ERROR: (Address|Leak)Sanitizer|runtime error:|AddressSanitizer|bad_alloc|"
                              r"terminate called|Segmentation fault")


def judge(done, out, command):
    """What is wrong with a finished case ("" when nothing)."""
    if done is None:
        return "no end within the time limit"
    code = done.returncode
    if code < 0:
        return "killed by signal %d" % -code
    if code not in (0, 1, 2):
        # 3 means output that could not be written; every case's --out is a fresh, writable folder
        return "exit %d" % code
    report = SANITIZER_REPORT.search(done.stderr)
    if report:
        return "stderr reports '%s'" % report.group(0)
    if code == 2 and os.path.exists(out):
        return "exit 2 left %s behind" % sorted(os.listdir(out))[:5]
    if code == 2 and not done.stderr.strip():
        return "exit 2 without a message"
    return ""


def run_case(weavelab, index, seed, bases, workdir, timeout, keep, verbose):
    rng = random.Random("%d:%d" % (seed, index))
    args, what, case_dir, out = make_case(index, rng, bases, workdir)
    start = time.monotonic()
    try:
        done = subprocess.run([weavelab] + args, capture_output=True, timeout=timeout, cwd=case_dir, env=case_env())
        done.stderr = done.stderr.decode("utf-8", "replace")
    except subprocess.TimeoutExpired:
        done = None
    seconds = time.monotonic() - start
    problem = judge(done, out, args[0])
    code = None if done is None else done.returncode
    if problem and keep:
        kept = os.path.join(keep, os.path.basename(case_dir))
        shutil.copytree(case_dir, kept, dirs_exist_ok=True)
        with open(os.path.join(kept, "command.txt"), "w") as f:
            f.write(" ".join([weavelab] + args) + "\n" + ("" if done is None else done.stderr))
    else:
        shutil.rmtree(case_dir, ignore_errors=True)
    message = [] if done is None else [l for l in done.stderr.splitlines() if l.strip() and "--help" not in l][-1:]
    result = {"index": index, "command": args[0], "what": what, "code": code, "seconds": seconds, "problem": problem,
              "args": args, "message": message[0] if message else ""}
    if verbose:  # as each case ends: a campaign cut short still tells what it ran
        print("case %d %s (%s): exit %s in %.2f s %s%s" % (index, args[0], what, code, seconds, result["message"][:160],
                                                          " FAILED: " + problem if problem else ""), flush=True)
    return result


def case_env():
    env = dict(os.environ)
    # A sanitizer report must not pass for exit 1 (a numerical failure): its own exit code.
    for name in ("ASAN_OPTIONS", "UBSAN_OPTIONS"):
        env[name] = ":".join(filter(None, [env.get(name, ""), "exitcode=86"]))
    env["LSAN_OPTIONS"] = ":".join(filter(None, [env.get("LSAN_OPTIONS", ""), "exitcode=86"]))
    return env


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--weavelab", required=True, help="the weavelab executable")
    parser.add_argument("--cases", type=int, default=40, help="number of cases (default 40)")
    parser.add_argument("--first", type=int, default=0, help="index of the first case (to run one case again)")
    parser.add_argument("--indices", help="comma-separated case indices to run instead of --first/--cases")
    parser.add_argument("--seed", type=int, default=20261129, help="seed of the mutations")
    parser.add_argument("--timeout", type=float, default=60.0, help="time limit per case [s]")
    parser.add_argument("--jobs", type=int, default=1, help="cases run at once")
    parser.add_argument("--keep", help="folder that keeps every failing case with its command")
    parser.add_argument("--verbose", action="store_true", help="one line per case")
    a = parser.parse_args()
    weavelab = os.path.abspath(a.weavelab)
    start = time.monotonic()
    with tempfile.TemporaryDirectory(prefix="weavelab_fuzz_") as workdir:
        bases = Bases(weavelab, workdir, a.timeout)
        indices = [int(k) for k in a.indices.split(",")] if a.indices else range(a.first, a.first + a.cases)
        with ThreadPoolExecutor(max_workers=max(1, a.jobs)) as pool:
            results = list(pool.map(lambda k: run_case(weavelab, k, a.seed, bases, workdir, a.timeout, a.keep, a.verbose),
                                    indices))
    failures = [r for r in results if r["problem"]]
    tally = {}
    for r in results:
        tally.setdefault(r["command"], {}).setdefault(r["code"], 0)
        tally[r["command"]][r["code"]] += 1
    slowest = max(results, key=lambda r: r["seconds"])
    print("cli_fuzz: %d cases (seed %d, first %d) in %.1f s wall, slowest %.1f s (case %d, %s)" %
          (len(results), a.seed, a.first, time.monotonic() - start, slowest["seconds"], slowest["index"],
           slowest["command"]))
    for command, codes in tally.items():
        print("  %-15s %s" % (command, ", ".join("exit %s: %d" % (c, n) for c, n in sorted(codes.items(),
                                                                                         key=lambda x: str(x[0])))))
    for r in failures:
        print("FAILED case %d (%s, %s): %s\n  %s\n  %s" % (r["index"], r["command"], r["what"], r["problem"],
                                                        " ".join(r["args"]), r["message"][:300]))
    print("cli_fuzz: %d failures" % len(failures))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
