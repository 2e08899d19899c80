"""Models and manual stepping from Python: force, Jacobians, mass and energies at a
state, and a Simulation stepped to the frames of a run."""
import os
import subprocess
import sys
import unittest

import numpy as np

import weavelab
from support import SOURCE_DIR, small_scene


def moved_state(model, seed=3):
    """The initial state with every DoF nudged, so that every term is strained."""
    rng = np.random.default_rng(seed)
    q = model.initial_q + 1e-5 * rng.standard_normal(model.num_dofs)
    v = model.initial_v + 1e-2 * rng.standard_normal(model.num_dofs)
    return q, v


class ModelAtAState(unittest.TestCase):
    def check_jacobians(self, kind):
        scene = small_scene(weavelab, size=5)
        model = weavelab.Model(scene, kind)
        q, v = moved_state(model)
        e = model.evaluate(q, v, t=0.01)
        n = model.num_dofs
        self.assertEqual(e["force"].shape, (n,))
        self.assertEqual(e["dfdq"].shape, (n, n))
        rng = np.random.default_rng(7)
        for name, step in (("dfdq", 1e-7), ("dfdv", 1e-5)):
            d = rng.standard_normal(n)
            plus = (q + step * d, v) if name == "dfdq" else (q, v + step * d)
            minus = (q - step * d, v) if name == "dfdq" else (q, v - step * d)
            fd = (model.evaluate(*plus, t=0.01, jacobians=False, mass=False)["force"] -
                  model.evaluate(*minus, t=0.01, jacobians=False, mass=False)["force"]) / (2 * step)
            model.evaluate(q, v, t=0.01)  # the auxiliaries of the state again
            jd = e[name] @ d
            self.assertGreater(np.linalg.norm(jd), 0.0, name)
            # Friction's F_n and F_u are held frozen in the Jacobians (docs/models.md §5): a loose bound.
            self.assertLess(np.linalg.norm(jd - fd), 1e-2 * np.linalg.norm(jd), (kind, name))

    def test_yarn_jacobians_match_the_force(self):
        self.check_jacobians("yarn")

    def test_fem_jacobians_match_the_force(self):
        self.check_jacobians("fem")

    def test_energies_match_the_mass(self):
        model = weavelab.Model(small_scene(weavelab, size=5), "yarn")
        q, v = moved_state(model)
        e = model.evaluate(q, v)
        energies = model.energies(q, v)
        self.assertAlmostEqual(energies["kinetic_J"], 0.5 * v @ (e["mass"] @ v), delta=1e-12 * energies["kinetic_J"])
        self.assertGreater(energies["kinetic_J"], 0.0)
        self.assertNotEqual(energies["potential_J"], model.energies(model.initial_q, v)["potential_J"])

    def test_the_yarn_level_follows_the_cloth(self):
        self.assertEqual(weavelab.model_names(), ["yarn", "knit", "fem", "mixed"])
        knit = weavelab.load_scene(os.path.join(SOURCE_DIR, "experiments", "scenes", "knit_stockinette.toml"))
        self.assertEqual(weavelab.Model(knit).name, "knit")  # no kind: the scene's yarn level
        self.assertEqual(weavelab.Model(knit, "knit").name, "knit")
        self.assertEqual(weavelab.Model(small_scene(weavelab, size=5)).name, "yarn")
        with self.assertRaises(ValueError) as e:
            weavelab.Model(knit, "yarn")
        self.assertIn("cloth.pattern.kind", str(e.exception))
        self.assertIn("expected model 'knit' or 'fem'", str(e.exception))
        with self.assertRaises(ValueError) as e:
            weavelab.Model(small_scene(weavelab, size=5), "knit")
        self.assertIn("expected model 'yarn' or 'fem'", str(e.exception))

    def test_bad_state_size(self):
        model = weavelab.Model(small_scene(weavelab, size=5), "yarn")
        with self.assertRaises(ValueError):
            model.evaluate(np.zeros(3), np.zeros(3))

    def test_without_scipy_index_arrays(self):
        script = ("import sys; sys.modules['scipy'] = None\n"
                  "import weavelab, support\n"
                  "m = weavelab.Model(support.small_scene(weavelab, size=5), 'yarn')\n"
                  "e = m.evaluate(m.initial_q, m.initial_v)\n"
                  "print(type(e['dfdq']).__name__, sorted(e['dfdq']), e['dfdq']['shape'] == (m.num_dofs,) * 2)\n")
        done = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, check=True,
                              cwd=os.path.dirname(os.path.abspath(__file__)))
        self.assertEqual(done.stdout.strip(), "dict ['data', 'indices', 'indptr', 'shape'] True")


class Stepping(unittest.TestCase):
    def test_simulation_gives_the_frames_of_a_run(self):
        scene = small_scene(weavelab)
        run = weavelab.run(scene)
        sim = weavelab.Simulation(scene)
        for k, t in enumerate(run.times[1:], start=1):
            self.assertEqual(sim.advance_to(t)["outcome"], "ok")
            self.assertTrue(np.array_equal(sim.frame()["positions"], run.positions[k]), t)
        self.assertEqual(sim.stats()["steps"], run.summary["statistics"]["steps"])

    def test_step_advances_by_dt(self):
        scene = small_scene(weavelab)
        sim = weavelab.Simulation(scene)
        q0 = sim.q
        sim.step()
        sim.step()
        self.assertAlmostEqual(sim.t, 2 * scene.dt_s, delta=1e-15)
        self.assertEqual(sim.stats()["steps"], 2)
        self.assertGreater(np.abs(sim.q - q0).max(), 0.0)
        # The simulation's model reads the state reached.
        e = sim.model.evaluate(sim.q, sim.v, sim.t, jacobians=False, mass=False)
        self.assertTrue(np.all(np.isfinite(e["force"])))

    def test_any_integrator(self):
        scene = small_scene(weavelab, duration=0.005)
        for name in ("be-newton", "sdirk2"):
            run = weavelab.run(scene, integrator=name)
            self.assertEqual((run.outcome, run.summary["integrator"]["name"]), ("ok", name))


if __name__ == "__main__":
    unittest.main()
