"""The lab's yarn model with every [compat] switch on against each force term of the authors' published
code, stored in tests/data/published_code_terms_5x5.csv (their example at 5×5 nodes, one of its
states; the header names the commands that produced it). Per term the relative difference on the
positions and on the sliding coordinates must be below 1e-10 (docs/published_code.md: the compat terms
compute the published formulas). Friction is not reproduced (rows 3–4) and is not compared."""
import csv
import os
import unittest

import numpy as np

import weavelab
from support import SOURCE_DIR

DATA = os.path.join(SOURCE_DIR, "tests", "data", "published_code_terms_5x5.csv")
SCENE = os.path.join(SOURCE_DIR, "experiments", "published_code", "scenes", "authors_homogeneous_17.toml")
SIZE, TIME_S = 5, 0.029  # the stored state is step 29 of 1 ms
COMPAT = {"normal_force_stretch": "centre_line", "wind_diagonals": "alternating", "bending_sliding_force": "theta",
          "parallel_contact_sign": "attractive", "ring_over_under": "none", "shear_lock_angle": "actual",
          "shear_lock_derivative": "published", "shear_quadrants": "interior", "normal_force_bending_uv": "rest"}
# Lab term switch -> the published terms whose sum it computes.
TERMS = {"stretch": ["stretch"], "bending": ["bending"], "gravity": ["gravity"], "wind": ["wind"],
         "handles": ["handles"], "shear": ["shear"], "parallel_contact": ["parallel_contact"],
         "inertia": ["inertia_dT_dq", "inertia_mdot_qdot"]}
SWITCHES = list(TERMS) + ["friction"]


def read_data():
    with open(DATA, newline="") as f:
        rows = list(csv.DictReader(line for line in f if not line.startswith("#")))
    table = {}
    for r in rows:
        values = [float(r[k]) if r[k] else 0.0 for k in "abcde"]
        table.setdefault(r["row"], {})[(int(r["i"]), int(r["j"]))] = values
    return table


def lab_dofs():
    """(i, j) -> offsets of x and, at interior crossings, of u and v, in the lab's DoF order."""
    out, k = {}, 0
    for j in range(SIZE):
        for i in range(SIZE):
            interior = 0 < i < SIZE - 1 and 0 < j < SIZE - 1
            out[(i, j)] = (k, k + 3 if interior else None)
            k += 5 if interior else 3
    return out, k


def vector(values, dofs, size):
    """The lab's DoF vector of per-node rows (x, y, z, u, v)."""
    out = np.zeros(size)
    for key, (x, uv) in dofs.items():
        out[x:x + 3] = values[key][:3]
        if uv is not None:
            out[uv:uv + 2] = values[key][3:]
    return out


class PublishedTermsData(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.table = read_data()
        cls.dofs, cls.size = lab_dofs()
        scene = weavelab.load_scene(SCENE)
        scene.update({"cloth.warps": SIZE, "cloth.wefts": SIZE,
                      "handles": [{"node": [0, 0], "stiffness_N_per_m": 1e4},
                                  {"node": [SIZE - 1, 0], "stiffness_N_per_m": 1e4}]})
        for key, value in COMPAT.items():
            scene[f"compat.{key}"] = value
        cls.scene = scene
        cls.q = vector(cls.table["position"], cls.dofs, cls.size)
        cls.v = vector(cls.table["velocity"], cls.dofs, cls.size)
        cls.sliding = np.zeros(cls.size, dtype=bool)
        for _, uv in cls.dofs.values():
            if uv is not None:
                cls.sliding[uv:uv + 2] = True

    def lab_force(self, term):
        scene = self.scene.copy()
        for s in SWITCHES:
            scene[f"terms.{s}"] = s == term
        model = weavelab.Model(scene, "yarn")
        return np.asarray(model.evaluate(self.q, self.v, TIME_S, jacobians=False, mass=False)["force"])

    def test_every_term_matches_the_published_code(self):
        for term, names in TERMS.items():
            parts = [vector(self.table[name], self.dofs, self.size) for name in names]
            published, lab = sum(parts), self.lab_force(term)
            for rows, label in ((~self.sliding, "positions"), (self.sliding, "sliding")):
                # The published inertia is two parts that nearly cancel on the sliding rows: the scale is
                # that of the parts (their sum is at their rounding level there).
                scale = sum(np.linalg.norm(p[rows]) for p in parts)
                if scale == 0.0:
                    self.assertEqual(np.linalg.norm(lab[rows]), 0.0, f"{term} on the {label}")
                    continue
                with self.subTest(term=term, rows=label):
                    self.assertGreater(np.linalg.norm(lab[rows]), 0.0)
                    self.assertLess(np.linalg.norm(lab[rows] - published[rows]) / scale, 1e-10)

    def test_normal_force_matches_the_published_code(self):
        fn = np.asarray(weavelab.Model(self.scene, "yarn").frame(self.q, self.v, TIME_S)["F_n"]).reshape(-1)
        interior = [(i, j) for j in range(1, SIZE - 1) for i in range(1, SIZE - 1)]
        lab = np.array([fn[i + SIZE * j] for i, j in interior])
        published = np.array([self.table["normal_force"][key][0] for key in interior])
        self.assertGreater(np.linalg.norm(published), 0.0)
        self.assertLess(np.linalg.norm(lab - published) / np.linalg.norm(published), 1e-10)

    def test_default_model_differs(self):
        """The same comparison fails for the lab's own model (the switches matter at this state)."""
        scene = self.scene.copy()
        for key in COMPAT:
            del scene[f"compat.{key}"]
        for s in SWITCHES:
            scene[f"terms.{s}"] = s == "shear"
        lab = np.asarray(weavelab.Model(scene, "yarn").evaluate(self.q, self.v, TIME_S, jacobians=False,
                                                                 mass=False)["force"])
        published = vector(self.table["shear"], self.dofs, self.size)
        self.assertGreater(np.linalg.norm(lab - published) / np.linalg.norm(published), 1e-3)


if __name__ == "__main__":
    unittest.main()
