#!/usr/bin/python3
"""The tables of a `weavelab fit` folder (fit.json) for RESULTS.md.

    fit_tables.py DIR

Writes DIR/tables/parameters.csv (per fitted key its start, fitted value,
relative change and standard error) and DIR/tables/cost.csv (converged,
iterations, simulations, wall and CPU seconds, and the RMS distance to the
target at the start and at the end, the largest over the frames).
Missing or malformed input: a message, exit 2, nothing written.
"""
import json
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "common"))
import runs as wio  # noqa: E402


def number(v):
    return "" if v is None else f"{v:.6g}"


def main(argv):
    if len(argv) != 1:
        wio.fail(__doc__.strip().split("\n\n")[1].strip())
    path = os.path.join(argv[0], "fit.json")
    try:
        with open(path, encoding="utf-8") as f:
            meta = json.load(f)
        params = ["parameter,start,fitted,relative_change,std_error"]
        for p in meta["parameters"]:
            change = (p["value"] - p["start"]) / p["start"] if p["start"] else None
            params.append(f"{p['key']},{number(p['start'])},{number(p['value'])},{number(change)},"
                          f"{number(p['std_error'])}")
        cost = ["converged,iterations,simulations,wall_s,cpu_s,start_rms_m,final_rms_m",
                f"{'yes' if meta['converged'] else 'no'},{meta['iterations']},{meta['simulations']},"
                f"{number(meta['wall_s'])},{number(meta['cpu_s'])},{number(meta.get('start_rms_m'))},"
                f"{number(meta.get('final_rms_m'))}"]
    except OSError as e:
        wio.fail(f"{path}: {e.strerror} (run weavelab fit first)")
    except (ValueError, KeyError, TypeError) as e:
        wio.fail(f"{path}: malformed ({type(e).__name__}: {e})")
    os.makedirs(os.path.join(argv[0], "tables"), exist_ok=True)
    try:
        wio.write_text_atomically(os.path.join(argv[0], "tables", "parameters.csv"), "\n".join(params) + "\n")
        wio.write_text_atomically(os.path.join(argv[0], "tables", "cost.csv"), "\n".join(cost) + "\n")
    except wio.RunError as e:
        wio.fail(str(e))


if __name__ == "__main__":
    main(sys.argv[1:])
