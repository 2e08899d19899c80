#!/usr/bin/python3
"""Each force term of the lab against the published code's, at the published code's own states.

    compare_terms.py --published DIR --scene SCENE.toml [--variant NAME=LINE;LINE ...] --out CSV

DIR holds the driver's trajectory.csv (states) and forces.csv (each term's force at some steps).
For every step in forces.csv the lab's model (the Python module `weavelab`, PYTHONPATH=build/python)
is evaluated at the published state (positions, sliding coordinates and their rates) with one term
switched on at a time, and its generalized force compared with the published term's:
relative difference ‖f_lab − f_published‖ / ‖f_published‖ over the position rows and, separately,
over the sliding rows (u, v), with both norms. The published inertia is the sum of its two parts
(∂T/∂q and −Ṁq̇), which the lab computes as one term. `total` is every term on (the scene as it is):
it includes friction, whose anchors the lab holds at rest, so it is comparable at step 0 only.
A variant (NAME=LINE;LINE) adds a [compat] table of those lines (docs/published_code.md) and is
compared term by term as well. Row `normal_force` compares the contact normal force F_n of the
interior crossings (the frame's F_n, every term on) in the x columns.
Missing or malformed inputs: a message on stderr and exit 2.
"""
import argparse
import csv
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "common"))
import runs  # noqa: E402

# Lab term switch -> the published term names whose sum it is compared with.
TERMS = {
    "stretch": ["stretch"],
    "bending": ["bending"],
    "gravity": ["gravity"],
    "wind": ["wind"],
    "handles": ["handles"],
    "shear": ["shear"],
    "parallel_contact": ["parallel_contact"],
    "inertia": ["inertia_dT_dq", "inertia_mdot_qdot"],
}
ALL_SWITCHES = list(TERMS) + ["friction"]


def read_csv(path):
    if not os.path.isfile(path):
        runs.fail(f"'{path}' is missing: run the published driver first")
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def number(text):
    return float(text) if text not in ("", None) else None


def published_state(rows, step):
    """{(i, j): row} of the trajectory at a step."""
    nodes = {(int(r["i"]), int(r["j"])): r for r in rows if int(r["step"]) == step}
    if not nodes:
        runs.fail(f"trajectory.csv has no step {step}")
    return nodes


def layout(nu, nv):
    """Per node (i, j) in the lab's DoF order: (x offset, u offset or None, v offset or None)."""
    out, k = {}, 0
    for j in range(nv):
        for i in range(nu):
            interior = 0 < i < nu - 1 and 0 < j < nv - 1
            out[(i, j)] = (k, k + 3 if interior else None, k + 4 if interior else None)
            k += 5 if interior else 3
    return out, k


def state_vectors(nodes, dofs, size):
    q, v = np.zeros(size), np.zeros(size)
    for key, (x, u, w) in dofs.items():
        r = nodes[key]
        q[x:x + 3] = [float(r["x"]), float(r["y"]), float(r["z"])]
        v[x:x + 3] = [float(r["vx"]), float(r["vy"]), float(r["vz"])]
        if u is not None:
            q[u], q[w] = float(r["u"]), float(r["v"])
            v[u], v[w] = float(r["udot"]), float(r["vdot"])
    return q, v


def published_force(force_rows, step, names, dofs, size):
    f = np.zeros(size)
    for r in force_rows:
        if int(r["step"]) != step or r["term"] not in names:
            continue
        x, u, w = dofs[(int(r["i"]), int(r["j"]))]
        f[x:x + 3] += [float(r["fx"]), float(r["fy"]), float(r["fz"])]
        if u is not None:
            f[u] += float(r["fu"])
            f[w] += float(r["fv"])
    return f


def lab_force(weavelab, base, compat_lines, switches, q, v, t):
    scene = base.copy()
    for s in ALL_SWITCHES:
        scene[f"terms.{s}"] = s in switches
    for line in compat_lines:
        key, _, value = line.partition("=")
        scene[f"compat.{key.strip()}"] = value.strip().strip('"')
    model = weavelab.Model(scene, "yarn")
    return np.asarray(model.evaluate(q, v, t, jacobians=False, mass=False)["force"])


def lab_normal_force(weavelab, base, compat_lines, q, v, t, nu, nv):
    """F_n of the interior crossings (i + nu·j order, the ring left out) with every term on."""
    scene = base.copy()
    for line in compat_lines:
        key, _, value = line.partition("=")
        scene[f"compat.{key.strip()}"] = value.strip().strip('"')
    fn = np.asarray(weavelab.Model(scene, "yarn").frame(q, v, t)["F_n"]).reshape(-1)
    return np.array([fn[i + nu * j] for j in range(1, nv - 1) for i in range(1, nu - 1)])


def published_normal_force(force_rows, step, nu, nv):
    fn = {(int(r["i"]), int(r["j"])): float(r["fx"]) for r in force_rows
          if int(r["step"]) == step and r["term"] == "normal_force"}
    return np.array([fn[(i, j)] for j in range(1, nv - 1) for i in range(1, nu - 1)])


def relative(a, b, rows):
    ref = np.linalg.norm(b[rows])
    return (np.linalg.norm(a[rows] - b[rows]) / ref if ref > 0 else float("nan")), ref


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--published", required=True)
    parser.add_argument("--scene", required=True)
    parser.add_argument("--variant", action="append", default=[])
    parser.add_argument("--dt", type=float, default=1e-3)
    parser.add_argument("--out", required=True)
    args = parser.parse_args()
    import weavelab
    base = weavelab.load_scene(args.scene)
    traj = read_csv(os.path.join(args.published, "trajectory.csv"))
    forces = read_csv(os.path.join(args.published, "forces.csv"))
    nu, nv = base.wefts, base.warps
    dofs, size = layout(nu, nv)
    sliding = np.zeros(size, dtype=bool)
    for _, u, w in dofs.values():
        if u is not None:
            sliding[[u, w]] = True
    variants = [("lab_default", [])]
    for item in args.variant:
        name, sep, lines = item.partition("=")
        if not sep or not name:
            runs.fail(f"--variant '{item}': expected NAME=LINE;LINE")
        variants.append((name, [x for x in lines.split(";") if x.strip()]))
    out = []
    for step in sorted({int(r["step"]) for r in forces}):
        q, v = state_vectors(published_state(traj, step), dofs, size)
        comparisons = [(term, [term], names) for term, names in TERMS.items()]
        comparisons.append(("total", ALL_SWITCHES, ["total"]))
        for term, switches, names in comparisons:
            f_pub = published_force(forces, step, names, dofs, size)
            for variant, lines in variants:
                f_lab = lab_force(weavelab, base, lines, switches, q, v, step * args.dt)
                rx, nx = relative(f_lab, f_pub, ~sliding)
                ru, nuv = relative(f_lab, f_pub, sliding)
                out.append({"step": step, "term": term, "variant": variant, "relative_difference_x": rx,
                            "relative_difference_uv": ru, "published_norm_x": nx, "published_norm_uv": nuv})
        # The contact normal force F_n of the interior crossings (docs/published_code.md rows 1-2), in the x columns.
        fn_pub = published_normal_force(forces, step, nu, nv)
        for variant, lines in variants:
            fn_lab = lab_normal_force(weavelab, base, lines, q, v, step * args.dt, nu, nv)
            ref = np.linalg.norm(fn_pub)
            out.append({"step": step, "term": "normal_force", "variant": variant,
                        "relative_difference_x": np.linalg.norm(fn_lab - fn_pub) / ref if ref > 0 else float("nan"),
                        "relative_difference_uv": float("nan"), "published_norm_x": ref, "published_norm_uv": 0.0})
    with open(args.out, "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=list(out[0]))
        writer.writeheader()
        writer.writerows(out)


if __name__ == "__main__":
    main()
