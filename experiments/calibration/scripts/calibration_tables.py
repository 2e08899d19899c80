#!/usr/bin/python3
"""The tables of a `weavelab calibrate` folder (calibration.json) for RESULTS.md.

    calibration_tables.py DIR

Writes into DIR/tables/:
  parameters.csv  per [fem] parameter its start (first guess), fitted value,
                  standard error and whether it ended at a bound;
  tests.csv       per virtual test its points and the fit's relative RMS residual
                  (of the curve's range, or per point with --residuals relative);
  cost.csv        the fit's starts, iterations, curve evaluations and the wall
                  and CPU seconds of the yarn-level tests, the continuum tests,
                  the fit and the validation;
  validation.csv  (only when the calibration validated on motion) per scene and
                  continuum variant the mean and worst per-frame RMS distance to
                  the yarn level beside both sides' estimated time errors (mean
                  RMS, docs/models.md §7.8) and the verdict.
Missing or malformed input: a message, exit 2, nothing written.
"""
import json
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "common"))
import runs as wio  # noqa: E402


def csv_text(head, rows):
    def cell(v):
        if v is None:
            return ""
        if isinstance(v, bool):
            return "yes" if v else "no"
        if isinstance(v, float):
            return f"{v:.6g}"
        return str(v).replace(",", ";")
    return "\n".join([",".join(head)] + [",".join(cell(r.get(h)) for h in head) for r in rows]) + "\n"


def time_error(entry):
    te = entry.get("time_error") or entry.get("yarn_time_error") or {}
    return te.get("mean_rms_m")


def tables(meta):
    fit, timings = meta["fit"], meta["timings"]
    params = [{"parameter": p["key"], "first_guess": p["start"], "fitted": p["value"], "std_error": p["std_error"],
               "at_bound": p["at_bound"]} for p in meta["parameters"]]
    tests = [{"test": t["test"], "points": t["points"], "residual_rms_relative": t["residual_rms_relative"]}
             for t in meta["tests"]]
    cost = [{"starts": len(meta["starts"]), "iterations": fit["iterations"],
             "curve_evaluations": fit["curve_evaluations"], "yarn_tests_wall_s": timings["yarn_tests_wall_s"],
             "continuum_tests_wall_s": timings["fem_tests_wall_s"], "fit_wall_s": timings["fit_wall_s"],
             "fit_cpu_s": timings["fit_cpu_s"], "validation_wall_s": timings["validation_wall_s"]}]
    validation = []
    for scene in meta.get("validation", []):
        for v in scene["variants"]:
            validation.append({"scene": os.path.basename(scene["scene"]), "variant": v["variant"],
                               "mean_rms_m": v["mean_rms_m"], "worst_frame_rms_m": v["max_rms_m"],
                               "yarn_time_error_m": time_error(scene), "continuum_time_error_m": time_error(v),
                               "verdict": v["budget"]})
    return params, tests, cost, validation


def main(argv):
    if len(argv) != 1:
        wio.fail(__doc__.strip().split("\n\n")[1].strip())
    folder = argv[0]
    path = os.path.join(folder, "calibration.json")
    try:
        with open(path, encoding="utf-8") as f:
            meta = json.load(f)
        params, tests, cost, validation = tables(meta)
    except OSError as e:
        wio.fail(f"{path}: {e.strerror} (run weavelab calibrate first)")
    except (ValueError, KeyError, TypeError) as e:
        wio.fail(f"{path}: malformed ({type(e).__name__}: {e})")
    out = {"parameters.csv": csv_text(["parameter", "first_guess", "fitted", "std_error", "at_bound"], params),
           "tests.csv": csv_text(["test", "points", "residual_rms_relative"], tests),
           "cost.csv": csv_text(list(cost[0]), cost)}
    if validation:
        out["validation.csv"] = csv_text(list(validation[0]), validation)
    os.makedirs(os.path.join(folder, "tables"), exist_ok=True)
    try:
        for name, text in out.items():
            wio.write_text_atomically(os.path.join(folder, "tables", name), text)
    except wio.RunError as e:
        wio.fail(str(e))


if __name__ == "__main__":
    main(sys.argv[1:])
