#!/usr/bin/python3
"""Writes the suite's stored per-term forces of the published code at one of its states.

    term_data.py --published DIR --step K --command "..." --out CSV

DIR holds the published driver's trajectory.csv and forces.csv (a run whose DUMP_STEPS include K);
the CSV gets the state at step K (rows `position`: x, y, z, u, v; rows `velocity`: their rates) and
each term's generalized force there (rows named by the term: fx, fy, fz, fu, fv), after a header of
`#` lines holding the commands (--command, repeated) that built the driver and produced DIR.
Missing or malformed inputs: a message on stderr, exit 2.
"""
import argparse
import csv
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "common"))
import runs  # noqa: E402


def read_rows(path, step):
    if not os.path.isfile(path):
        runs.fail(f"'{path}' is missing: run the published driver first")
    with open(path, newline="") as f:
        rows = [r for r in csv.DictReader(f) if r.get("step") == str(step)]
    if not rows:
        runs.fail(f"'{path}' has no step {step}")
    return rows


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--published", required=True)
    parser.add_argument("--step", type=int, required=True)
    parser.add_argument("--command", action="append", required=True)
    parser.add_argument("--out", required=True)
    args = parser.parse_args()
    state = read_rows(os.path.join(args.published, "trajectory.csv"), args.step)
    forces = read_rows(os.path.join(args.published, "forces.csv"), args.step)
    with open(args.out + ".tmp", "w", newline="") as f:
        f.write("# Each term's generalized force of the published code of Gong et al. 2022 at one of its states\n"
                "# (the published_code study, docs/published_code.md), written by\n"
                "# experiments/published_code/scripts/term_data.py from the output of these commands:\n")
        for line in args.command:
            f.write(f"#   {line}\n")
        writer = csv.writer(f)
        writer.writerow(["row", "i", "j", "a", "b", "c", "d", "e"])
        for r in state:
            writer.writerow(["position", r["i"], r["j"], r["x"], r["y"], r["z"], r["u"], r["v"]])
        for r in state:
            writer.writerow(["velocity", r["i"], r["j"], r["vx"], r["vy"], r["vz"], r["udot"], r["vdot"]])
        for r in forces:
            writer.writerow([r["term"], r["i"], r["j"], r["fx"], r["fy"], r["fz"], r["fu"], r["fv"]])
    os.replace(args.out + ".tmp", args.out)


if __name__ == "__main__":
    main()
