#!/usr/bin/python3
"""The tables of the diagnosis study for RESULTS.md, from a `weavelab diagnose`
folder and `weavelab modes` folders.

    diagnosis_tables.py OUT DIAGNOSE_DIR FROM_S TO_S MODES_ROWS LABEL=MODES_DIR ...

Writes into OUT:
  budget.csv      the mean RMS distance between the yarn crossings and the
                  continuum (all, border, interior crossings) beside both runs'
                  estimated time errors (mean RMS) and the verdict (diagnosis.json);
  directions.csv  per term (stretch, bending) the change of each model's warp and
                  weft energy since t = 0, averaged over the frames in [FROM_S, TO_S]
                  (energy_directions.csv);
  modes.csv       the lowest MODES_ROWS yarn-level modes: frequency, and per
                  LABEL the continuum partner's mode, frequency and MAC (modes.csv);
  equilibria.csv  per LABEL and model: the equilibrium's route, Newton iterations
                  and residual, the planar hang's lowest frequency, stability and
                  the assembled stiffness's asymmetry, and the RMS distance
                  between the two models' equilibria (modes.json).
Missing or malformed input: a message, exit 2, nothing written.
"""
import csv
import json
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "common"))
import runs as wio  # noqa: E402


def read_csv(path):
    try:
        with open(path, newline="", encoding="utf-8") as f:
            return list(csv.DictReader(f))
    except OSError as e:
        raise wio.RunError(f"{path}: {e.strerror}") from None


def read_json(path):
    try:
        with open(path, encoding="utf-8") as f:
            return json.load(f)
    except OSError as e:
        raise wio.RunError(f"{path}: {e.strerror}") from None
    except ValueError as e:
        raise wio.RunError(f"{path}: not JSON ({e})") from None


def number(v):
    if v is None or v == "":
        return ""
    if isinstance(v, bool):
        return "yes" if v else "no"
    return f"{float(v):.6g}" if isinstance(v, (int, float)) else str(v).replace(",", ";")


def table(head, rows):
    return "\n".join([",".join(head)] + [",".join(number(r.get(h)) for h in head) for r in rows]) + "\n"


def budget(folder):
    meta = read_json(os.path.join(folder, "diagnosis.json"))
    error = lambda model: (meta.get(f"{model}_time_error") or {}).get("mean_rms_m")
    row = {"scene": os.path.basename(meta["scene"]["file"]), "resolution": meta["resolution"],
           "distance_mean_rms_m": meta["distance_mean_rms_m"], "border_rms_m": meta["border_rms_m"],
           "interior_rms_m": meta["interior_rms_m"], "yarn_time_error_m": error("yarn"),
           "continuum_time_error_m": error("fem"), "verdict": meta["verdict"]}
    return table(list(row), [row])


def directions(folder, t_from, t_to):
    """Mean over [t_from, t_to] of each (model, term kind, direction)'s change since t = 0."""
    series = {}
    for r in read_csv(os.path.join(folder, "energy_directions.csv")):
        kind = "bending" if r["term"].endswith("bending") else "stretch"
        for direction in ("warp", "weft"):
            by_time = series.setdefault((r["model"], kind, direction), {})
            t = float(r["time_s"])
            by_time[t] = by_time.get(t, 0.0) + float(r[f"{direction}_J"])
    rows = []
    for kind in ("bending", "stretch"):
        row = {"energy": kind}
        for model in ("yarn", "fem"):
            for direction in ("warp", "weft"):
                by_time = series.get((model, kind, direction))
                if not by_time:
                    raise wio.RunError(f"{folder}/energy_directions.csv: no {model} {kind} rows")
                start = by_time[min(by_time)]
                window = [e - start for t, e in by_time.items() if t_from - 1e-12 <= t <= t_to + 1e-12]
                if not window:
                    raise wio.RunError(f"{folder}/energy_directions.csv: no frame in [{t_from}, {t_to}] s")
                row[f"{model}_{direction}_J"] = sum(window) / len(window)
        rows.append(row)
    return table(list(rows[0]), rows)


def modes(count, labelled):
    yarn_rows = None
    partners = {}
    for label, folder in labelled:
        rows = read_csv(os.path.join(folder, "modes.csv"))
        yarn = {int(r["mode"]): r for r in rows if r["model"] == "yarn"}
        yarn_rows = yarn_rows or yarn
        partners[label] = yarn
    out = []
    for k in sorted(yarn_rows)[:count]:
        row = {"yarn_mode": k, "yarn_hz": yarn_rows[k]["frequency_hz"]}
        for label, _ in labelled:
            p = partners[label].get(k)
            row[f"{label}_partner"] = p["paired_mode"] if p else ""
            row[f"{label}_partner_hz"] = p["paired_frequency_hz"] if p else ""
            row[f"{label}_mac"] = p["mac"] if p else ""
        out.append(row)
    head = ["yarn_mode", "yarn_hz"] + [f"{label}_{c}" for label, _ in labelled for c in ("partner", "partner_hz", "mac")]
    text = [",".join(head)] + [",".join(str(r[h]) for h in head) for r in out]
    return "\n".join(text) + "\n"


def equilibria(labelled):
    rows = []
    for label, folder in labelled:
        meta = read_json(os.path.join(folder, "modes.json"))
        for model in ("yarn", "fem"):
            m = meta[model]
            rows.append({"continuum": label, "model": model, "equilibrium": m["equilibrium"],
                         "newton_iterations": m["equilibrium_newton_iterations"],
                         "residual_N": m["equilibrium_residual_N"], "planar_hang_lowest_hz": m["planar_hang_lowest_hz"],
                         "stable": m["stable"], "stiffness_asymmetry": m["stiffness_asymmetry"],
                         "equilibria_rms_distance_m": meta["equilibria_rms_distance_m"]})
    return table(list(rows[0]), rows)


def main(argv):
    if len(argv) < 6 or any("=" not in a for a in argv[5:]):
        wio.fail(__doc__.strip().split("\n\n")[1].strip())
    out, diagnose = argv[0], argv[1]
    try:
        t_from, t_to, count = float(argv[2]), float(argv[3]), int(argv[4])
    except ValueError:
        wio.fail(f"FROM_S TO_S MODES_ROWS: got '{argv[2]} {argv[3]} {argv[4]}', expected two numbers and an integer")
    labelled = [tuple(a.split("=", 1)) for a in argv[5:]]
    try:
        texts = {"budget.csv": budget(diagnose), "directions.csv": directions(diagnose, t_from, t_to),
                 "modes.csv": modes(count, labelled), "equilibria.csv": equilibria(labelled)}
    except wio.RunError as e:
        wio.fail(str(e))
    except (KeyError, TypeError, ValueError) as e:
        wio.fail(f"malformed input ({type(e).__name__}: {e})")
    os.makedirs(out, exist_ok=True)
    try:
        for name, text in texts.items():
            wio.write_text_atomically(os.path.join(out, name), text)
    except wio.RunError as e:
        wio.fail(str(e))


if __name__ == "__main__":
    main(sys.argv[1:])
