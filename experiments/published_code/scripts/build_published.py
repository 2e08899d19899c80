#!/usr/bin/python3
"""Fetch and build the authors' published yarn-level code with this study's driver.

The authors' sources are exported into a scratch folder outside the repository (given on the
command line, from the study's config) and compiled there with Debian's libtorch, Eigen and
OpenMP; nothing of theirs is copied into the repository. Only the translation units the
simulation needs are built (no training, rendering, HDF5 or collision code).

    build_published.py --source GIT_URL_OR_BARE_GIT_DIR --commit REV --scratch DIR \
        --driver experiments/published_code/scripts/published_driver.cpp --jobs 2

Writes DIR/published_driver (the program) and DIR/provenance.txt (source and commit).
Needs the Debian packages libtorch-dev and libeigen3-dev. Exit 2 on bad arguments or a
missing dependency, 1 when fetching or compiling fails.
"""
import argparse
import os
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor

UNITS = ["Cloth", "PhysicsCloth", "MatrixMp", "Solvers", "Mesh", "Geometry", "Obstacle"]
INCLUDES = ["/usr/include/eigen3", "/usr/include/torch/csrc/api/include"]
LIBS = ["-ltorch", "-ltorch_cpu", "-lc10"]
# Adaptations of the exported sources to Debian's libtorch (1.13; the authors used 1.9), applied in
# the scratch folder: (file, text, replacement). Neither touches the simulation's arithmetic.
PATCHES = [
    # torch::linalg::solve gained a required `left` argument; this helper is unused by the simulation.
    ("Solvers.h", "torch::linalg::solve(A, b)", "torch::linalg::solve(A, b, true)"),
]


def fail(message, code):
    print(f"build_published.py: {message}", file=sys.stderr)
    sys.exit(code)


def run(command, cwd=None):
    result = subprocess.run(command, cwd=cwd, capture_output=True, text=True)
    if result.returncode != 0:
        fail(f"{' '.join(command)} failed:\n{result.stderr[-4000:]}", 1)
    return result.stdout


def exported_commit(scratch):
    """The commit an earlier build exported into scratch (provenance.txt), or None."""
    try:
        with open(os.path.join(scratch, "provenance.txt")) as note:
            for line in note:
                key, _, value = line.strip().partition(" ")
                if key == "commit":
                    return value
    except OSError:
        return None
    return None


def export_sources(source, commit, scratch):
    """Exports src/ of the given commit into scratch/src; returns the full commit hash."""
    if os.path.isdir(source) and os.path.isfile(os.path.join(source, "HEAD")):
        git_dir = source
    else:
        git_dir = os.path.join(scratch, "repo.git")
        if not os.path.isdir(git_dir):
            run(["git", "clone", "--bare", "--filter=blob:limit=1m", source, git_dir])
    full = run(["git", f"--git-dir={git_dir}", "rev-parse", f"{commit}^{{commit}}"]).strip()
    if exported_commit(scratch) == full and os.path.isdir(os.path.join(scratch, "src")):
        return full  # already exported (and adapted): keep the files and their times, so nothing recompiles
    archive = subprocess.run(["git", f"--git-dir={git_dir}", "archive", full, "src"], capture_output=True)
    if archive.returncode != 0:
        fail(f"git archive of {full} failed: {archive.stderr.decode()[-2000:]}", 1)
    subprocess.run(["tar", "-x", "-C", scratch], input=archive.stdout, check=True)
    for name, text, replacement in PATCHES:
        path = os.path.join(scratch, "src", name)
        with open(path) as source_file:
            content = source_file.read()
        if text not in content:
            fail(f"{name}: the text to adapt ({text}) is not there; another revision of the sources?", 1)
        with open(path, "w") as source_file:
            source_file.write(content.replace(text, replacement))
    # One of their files includes a header under a different letter case (fine on Windows only).
    shim = os.path.join(scratch, "shim")
    os.makedirs(shim, exist_ok=True)
    with open(os.path.join(shim, "matrixMp.h"), "w") as header:
        header.write('#include "MatrixMp.h"\n')
    return full


def compile_unit(source_file, object_file, scratch):
    flags = ["-std=c++17", "-O2", "-DNDEBUG", "-fopenmp", "-w",
             "-I", os.path.join(scratch, "src"), "-I", os.path.join(scratch, "shim")]
    for include in INCLUDES:
        flags += ["-I", include]
    if os.path.exists(object_file) and os.path.getmtime(object_file) > os.path.getmtime(source_file):
        return object_file
    run(["nice", "g++", *flags, "-c", source_file, "-o", object_file])
    return object_file


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--source", required=True)
    parser.add_argument("--commit", default="HEAD")
    parser.add_argument("--scratch", required=True)
    parser.add_argument("--driver", required=True)
    parser.add_argument("--jobs", type=int, default=1)
    args = parser.parse_args()
    if not os.path.isfile(args.driver):
        fail(f"--driver {args.driver}: no such file", 2)
    for include in INCLUDES:
        if not os.path.isdir(include):
            fail(f"{include} missing: install the Debian packages libtorch-dev and libeigen3-dev", 2)
    if args.jobs < 1:
        fail(f"--jobs {args.jobs}: expected a positive count", 2)
    scratch = os.path.abspath(args.scratch)
    os.makedirs(scratch, exist_ok=True)
    commit = export_sources(args.source, args.commit, scratch)
    jobs = [(os.path.join(scratch, "src", f"{unit}.cpp"), os.path.join(scratch, f"{unit}.o")) for unit in UNITS]
    jobs.append((os.path.abspath(args.driver), os.path.join(scratch, "published_driver.o")))
    with ThreadPoolExecutor(max_workers=args.jobs) as pool:
        objects = list(pool.map(lambda job: compile_unit(job[0], job[1], scratch), jobs))
    program = os.path.join(scratch, "published_driver")
    run(["g++", "-fopenmp", *objects, "-o", program, *LIBS])
    with open(os.path.join(scratch, "provenance.txt"), "w") as note:
        note.write(f"source {args.source}\ncommit {commit}\n")
    print(program)


if __name__ == "__main__":
    main()
