#!/usr/bin/env python3
"""Markdown table of the trajectory-fit study: per parameter the ground truth
(the scene's value), Gong et al. 2022's recovered value (Table 2, 17×17
Plain-(1,2), 25 frames), ours from 5, 10 and 25 frames (protocol start) and
the mean ± std over the random starts from 5 and 25 frames, with relative errors
(the largest over the random starts), wall and CPU times, the stages of a
growing window, and the distance to the target beside the fitted run's time error.
Then, for the fits named slide_* (μ where yarns slide, the slide_pull scene),
each free parameter's truth, start and fitted value with the fit's cost.
Usage: fit_paper_table.py DIR ... (the folders holding the fits, NAME/fit.json
or NAME/start_K/fit.json; a folder that does not exist holds none)
"""
import glob
import json
import os
import statistics
import sys
import tomllib

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "common"))
from runs import fail  # noqa: E402

# Gong et al. 2022, Table 2, 17×17 row (learned on the first 25 frames).
PAPER = {
    "contact.shear_modulus_Pa": 947, "contact.friction_coefficient": 0.402,
    "yarn_types.yarn1.density_kg_per_m": 1.969e-3, "yarn_types.yarn1.stretch_modulus_Pa": 505421,
    "yarn_types.yarn1.bending_modulus_Pa": 1.323e-4, "yarn_types.yarn2.density_kg_per_m": 2.440e-3,
    "yarn_types.yarn2.stretch_modulus_Pa": 171304, "yarn_types.yarn2.bending_modulus_Pa": 1.034e-4,
}
PAPER_HOURS_PER_FIT = "≈ 6.4 h (paper, GPU machine)"
NO_STD_ERROR = "¹ no standard error: the frames do not determine it (the fit cannot tell it; it stays near its start)."


def truth(scene_text, key):
    t = tomllib.loads(scene_text)
    for part in key.split("."):
        t = t[part]
    return float(t)


def load(path):
    with open(path) as f:
        return json.load(f)


def rel(value, true):
    return f"{100 * abs(value - true) / abs(true):.2g} %"


def main():
    if len(sys.argv) < 2:
        fail("usage: fit_paper_table.py DIR ...")
    runs = {}
    for d in sys.argv[1:]:
        found = glob.glob(os.path.join(d, "*", "fit.json")) + glob.glob(os.path.join(d, "*", "start_*", "fit.json"))
        for p in found:
            name = os.path.relpath(os.path.dirname(p), d)
            if name in runs:
                fail(f"{p}: a fit named {name} is in two folders")
            runs[name] = load(p)
    protocol = [runs.get(f"protocol_{n}") for n in (5, 10, 25)]
    randoms = [[r for name, r in sorted(runs.items()) if name.startswith(f"random_{n}/")] for n in (5, 25)]
    slides = sorted(((n, r) for n, r in runs.items() if n.startswith("slide_")), key=lambda x: (len(x[1]["parameters"]), x[0]))
    if not any(protocol) and not slides:
        fail(f"{', '.join(sys.argv[1:])}: no protocol_N/fit.json or slide_NAME/fit.json (run the trajectory_fit study)")
    if any(protocol):
        hanging_table(protocol, randoms)
    if slides:
        slide_table(slides)


def slide_table(slides):
    """μ where yarns slide: per fit, each free parameter's truth, start, value and
    standard error, with the fit's convergence, cost and time error budget."""
    print("\n**Where yarns slide** (slide_pull scene; μ first, then the other free parameters)\n")
    head = "| fit | parameter | truth | start | fitted (error) | std. error | converged, iterations, sim., wall / CPU |"
    print(head)
    print("|" + "---|" * (head.count("|") - 1))
    for name, run in slides:
        scene = run["scene"]["text"]
        budget = run.get("error_budget", {})
        status = (f"{'yes' if run['converged'] else 'no'}, {run['iterations']} it., {run['simulations']} sim., "
                  f"{run['wall_s']:.1f} s / {run['cpu_s']:.1f} s CPU")
        for p in run["parameters"]:
            t = truth(scene, p["key"])
            se = f"{p['std_error']:.2g}" if p.get("std_error") is not None else "– ¹"
            key = p["key"].replace("yarn_types.", "").replace("contact.", "")
            print(f"| {name} ({run['frames']} fr.) | {key} | {t:.4g} | {p['start']:.4g} | "
                  f"{p['value']:.6g} ({rel(p['value'], t)}) | {se} | {status} |")
            status = ""
        if isinstance(budget.get("distance_mean_rms_m"), (int, float)):
            te = budget.get("fitted_time_error", {})
            te = te.get("mean_rms_m") if isinstance(te, dict) else None
            tt = budget.get("target_time_error_mean_rms_m")
            tes = lambda x: f"{1e3 * x:.3g} mm" if isinstance(x, (int, float)) else "–"
            print(f"| {name} | distance to target (mean RMS) | | | {tes(budget['distance_mean_rms_m'])} | "
                  f"time error: fitted {tes(te)}, target {tes(tt)} | |")
    if any(p.get("std_error") is None for _, run in slides for p in run["parameters"]):
        print(f"\n{NO_STD_ERROR}")


def stages(run):
    """'5·10·25 fr.: 6·2·2 it., 7·3·3 sim.' for a growing window, else ''."""
    st = run.get("stages", [])
    if len(st) < 2:
        return ""
    dot = lambda k: "·".join(str(s[k]) for s in st)
    return f"; {dot('frames')} fr.: {dot('iterations')} it., {dot('simulations')} sim."


def distance(run):
    """The fitted run's mean RMS distance to the target beside its time error (fit.json error_budget)."""
    b = run.get("error_budget", {})
    te = b.get("fitted_time_error", {})
    te = te.get("mean_rms_m") if isinstance(te, dict) else None
    mm = lambda x: f"{1e3 * x:.2g} mm" if isinstance(x, (int, float)) else "–"
    return f"{mm(b.get('distance_mean_rms_m'))} / {mm(te)}"


def hanging_table(protocol, randoms):
    scene = next(r for r in protocol + [r for rs in randoms for r in rs] if r)["scene"]["text"]
    value = lambda run, key: next(p["value"] for p in run["parameters"] if p["key"] == key)
    ident = lambda run, key: next(p.get("std_error") is not None for p in run["parameters"] if p["key"] == key)
    window = lambda run: " (window " + ", ".join(str(s["frames"]) for s in run["stages"]) + ")" \
        if run and len(run.get("stages", [])) > 1 else ""
    head = ("| parameter | truth | paper (25 fr.) | ours 5 fr. | ours 10 fr. | ours 25 fr." + window(protocol[2]) +
            " | random starts, 5 fr. | random starts, 25 fr." + window(next(iter(randoms[1]), None)) + " |")
    print(head)
    print("|" + "---|" * (head.count("|") - 1))
    for key, paper in PAPER.items():
        t = truth(scene, key)
        cells = [key.replace("yarn_types.", "").replace("contact.", ""), f"{t:.4g}", f"{paper:.4g} ({rel(paper, t)})"]
        for run in protocol:
            if not run:
                cells.append("–")
                continue
            v = value(run, key)
            cells.append(f"{v:.4g} ({rel(v, t)})" + ("" if ident(run, key) else " ¹"))
        for rs in randoms:
            if not rs:
                cells.append("–")
                continue
            vs = [value(r, key) for r in rs]
            sd = statistics.stdev(vs) if len(vs) > 1 else 0.0
            worst = max(vs, key=lambda v: abs(v - t))
            cells.append(f"{statistics.mean(vs):.4g} ± {sd:.2g} (≤ {rel(worst, t)})" +
                         ("" if all(ident(r, key) for r in rs) else " ¹"))
        print("| " + " | ".join(cells) + " |")
    times = [f"{r['wall_s'] / 60:.1f} / {r['cpu_s'] / 60:.1f} min, {r['iterations']} it., {r['simulations']} sim."
             + stages(r) if r else "–" for r in protocol]
    def per_start(rs):
        if not rs:
            return "–"
        minutes = lambda k: "·".join(f"{r[k] / 60:.1f}" for r in rs)
        return f"{minutes('wall_s')} / {minutes('cpu_s')} min, {'·'.join(str(r['simulations']) for r in rs)} sim. ²"
    rt = [per_start(rs) for rs in randoms]
    print(f"| wall / CPU time per fit | | {PAPER_HOURS_PER_FIT} | " + " | ".join(times + rt) + " |")
    dist = [distance(r) if r else "–" for r in protocol] + [", ".join(distance(r) for r in rs) or "–" for rs in randoms]
    print("| distance to the target (mean RMS) / the fitted run's time error | | | " + " | ".join(dist) + " |")
    print(f"\n{NO_STD_ERROR}")
    if any(randoms):
        print("² per start, from one command with --jobs: while two fits run at once each one's wall time is shared "
              "and its CPU time is the process's (both fits').")


if __name__ == "__main__":
    main()
