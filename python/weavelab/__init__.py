"""weavelab from Python: scenes, models, runs, calibrate and fit (docs/python.md).

    import weavelab
    scene = weavelab.load_scene("experiments/scenes/hanging_wind.toml")
    scene["time.duration_s"] = 0.1
    run = weavelab.run(scene)
    print(run.positions.shape, run.summary["result"]["outcome"])

A thin layer over the compiled core (weavelab._core, python/bindings/): the
runs are the run driver's (`weavelab run`), the checks the scene parser's.
"""
import json
import os
import warnings

from weavelab._core import (Model, Scene, SceneError, SettingError, integrator_capabilities, integrator_names,
                            model_names)
from weavelab import _core

try:
    import scipy.sparse as _sparse
except ImportError:  # Jacobians then come as their compressed-column arrays
    _sparse = None

__all__ = ["Scene", "Model", "Simulation", "Run", "Interrupted", "SceneError", "SettingError", "load_scene",
           "run", "calibrate", "fit", "integrator_names", "integrator_capabilities", "model_names", "sparse_matrix"]


class Interrupted(KeyboardInterrupt):
    """Ctrl-C (SIGINT) or SIGTERM during a run: the step under way ended, then the
    run stopped; `.run` holds what it had (outcome "interrupted"; of calibrate
    and fit, the dict of their record), as the command line keeps its record."""

    def __init__(self, message, run=None):
        super().__init__(message)
        self.run = run


def load_scene(path):
    """Reads and validates a scene file (TOML); weavelab.SceneError names file, line and key."""
    return Scene.load(os.fspath(path))


def sparse_matrix(arrays):
    """A Jacobian or mass matrix of Model.evaluate: a scipy.sparse.csc_matrix when
    scipy is importable, otherwise the dict of its compressed-column arrays
    (shape, indptr, indices, data)."""
    if _sparse is None:
        return arrays
    return _sparse.csc_matrix((arrays["data"], arrays["indices"], arrays["indptr"]), shape=arrays["shape"])


def _evaluate(self, q, v, t=0.0, jacobians=True, mass=True):
    """Force f(t, q, v) and, on request, the Jacobians df/dq, df/dv and the mass
    matrix M(q) (scipy.sparse or index arrays, see sparse_matrix). Evaluating
    sets the model's auxiliaries (contact normals, frozen friction)."""
    out = _core.Model._evaluate_arrays(self, q, v, t, jacobians, mass)
    for key in ("dfdq", "dfdv", "mass"):
        if key in out:
            out[key] = sparse_matrix(out[key])
    return out


Model._evaluate_arrays = Model.evaluate
Model.evaluate = _evaluate


class Run:
    """A finished run: frames as numpy arrays (first axis the frame, t = 0
    included) and the run summary (summary.json) as a dict."""

    def __init__(self, raw):
        self.times = raw.pop("time")
        self.positions = raw.pop("positions")           # frames × nodes × 3 [m]
        self.velocities = raw.pop("velocities", None)   # frames × nodes × 3 [m/s]
        self.cells = raw.pop("cells")                   # {"line"|"triangle"|"quad": cells × k}
        self.outcome = raw.pop("outcome")
        self.message = raw.pop("message")
        self.end_time = raw.pop("end_time")
        self.summary = json.loads(raw.pop("summary_json"))
        self.out = raw.pop("out")
        self.point_data = raw  # the other point data: "u", "v" (sliding coordinates [m]), "F_n", "sliding", …

    @property
    def measures(self):
        """What the scene's [measures] asked for, taken on the last frame (summary.json
        "measures", docs/models.md §3.11.6), e.g. measures["drape"]["coefficient"]; {} when none."""
        return self.summary.get("measures", {})

    @property
    def u(self):
        """Sliding coordinate along the warp per frame and node [m] (yarn model)."""
        return self.point_data.get("u")

    @property
    def v(self):
        """Sliding coordinate along the weft per frame and node [m] (yarn model)."""
        return self.point_data.get("v")

    def __repr__(self):
        return "<weavelab.Run %s: %d frames to t = %g s>" % (self.outcome, len(self.times), self.end_time)


def run(scene, model=None, *, integrator=None, dt=None, duration=None, output_interval=None, adaptive=False,
        rtol=None, linear_solver=None, error_estimate=False, accuracy=None, fem_params=None, out=None,
        progress=False):
    """Runs `scene` (a Scene or a path) like `weavelab run`: each keyword is the
    twin of its command-line option and obeys its rules (a duration or dt
    shorter than the scene's output interval shrinks the interval, with a
    notice). With `out` the run also writes its folder (frames, metrics.csv,
    summary.json); without, nothing is written. `model` is "yarn" (woven),
    "knit", "fem" or "mixed"; None is the scene's yarn level ("yarn" or "knit"). Returns
    a Run; a numerical failure is its outcome, Ctrl-C raises
    weavelab.Interrupted holding it."""
    if not isinstance(scene, Scene):
        scene = load_scene(scene)
    raw = _core._run(scene, model or "", None if out is None else os.fspath(out), progress, integrator, linear_solver, dt,
                     duration, output_interval, adaptive, rtol, error_estimate, accuracy,
                     None if fem_params is None else os.fspath(fem_params))
    result = Run(raw)
    if result.outcome == "interrupted":
        raise Interrupted(result.message, result)
    return result


class Simulation(_core._Simulation):
    """A model and the scene's integrator ([time] integrator, dt_s, adaptive,
    rtol, atol), stepped from Python: step() advances by dt_s (one step of a
    fixed-step method; the last one ends at the scene's duration),
    advance_to(t) to a time from t to the scene's duration (ValueError
    otherwise); q, v, t, frame() and model (for Model.evaluate at the current
    state) read it. `model` None is
    the scene's yarn level ("yarn" for a woven, "knit" for a knitted cloth)."""

    def __init__(self, scene, model=None):
        super().__init__(scene, model or "")

    def _check(self, result):
        if result["outcome"] == "interrupted":
            raise Interrupted(result["message"])
        return result

    def step(self):
        """Advances by the scene's dt_s; returns {"outcome", "message"}."""
        return self._check(super().step())

    def advance_to(self, t):
        """Advances to time t [s], at most the scene's duration; returns {"outcome", "message"}."""
        return self._check(super().advance_to(t))


def _scene_file(scene, out):
    """A scene file for the drivers that read one: the file of an unedited
    Scene, else the Scene's text written to OUT/scene.toml."""
    if not isinstance(scene, Scene):
        return os.fspath(scene)
    if not scene.edited:
        return scene.source
    os.makedirs(out, exist_ok=True)
    path = os.path.join(out, "scene.toml")
    with open(path, "w") as f:
        f.write(scene.toml)
    return path


def _read_json(path):
    with open(path) as f:
        return json.load(f)


def calibrate(scene, out, *, tests=(), free=(), patch=0, ladders=None, starts=4, seed=1, loss="none",
              sliding=False, border_strip=False, validate=(), time_steps="controlled", rtol=1e-4, progress=False,
              resolution=None):
    """`weavelab calibrate` (README, docs/calibration.md): fits the continuum's
    [fem] parameters to virtual tests of the scene's fabric and writes OUT
    (params.toml, calibration.json, curves.csv, validation.csv). `time_steps`
    is `--time-steps` ("controlled" or "scene"); `resolution`, its old name,
    still works with a DeprecationWarning. Returns calibration.json as a dict,
    with "out" and "converged" added."""
    if resolution is not None:
        warnings.warn("calibrate(resolution=...) is deprecated: use time_steps=...", DeprecationWarning, stacklevel=2)
        time_steps = resolution
    out = os.fspath(out)
    converged = _core._calibrate(_scene_file(scene, out), out, list(tests), list(free), patch, dict(ladders or {}),
                                 starts, seed, loss, sliding, border_strip, [os.fspath(p) for p in validate],
                                 time_steps, rtol, progress)
    result = _read_json(os.path.join(out, "calibration.json"))
    result.update(out=out, converged=converged)
    if result["outcome"] == "interrupted":
        raise Interrupted(result["message"], result)
    return result


def fit(scene, target, free, out, *, start=None, frames=0, model=None, integrator="", bound_factor=100.0,
        max_iterations=50, fem_params="", window=(), progress=False):
    """`weavelab fit`: fits scene keys (`free`) to the frames of the run folder
    `target` (a run with out=...) and writes OUT (fit.json, convergence.csv,
    frames.csv); `window` = (N1, N2, ...) is `--growing-window`; `model` None
    is the scene's yarn level. Returns fit.json as a dict, with "out" and
    "converged" added."""
    out = os.fspath(out)
    converged = _core._fit(_scene_file(scene, out), os.fspath(target), list(free), out, dict(start or {}), frames,
                           model or "", integrator, bound_factor, max_iterations, os.fspath(fem_params), list(window),
                           progress)
    result = _read_json(os.path.join(out, "fit.json"))
    result.update(out=out, converged=converged)
    if result["outcome"] == "interrupted":
        raise Interrupted(result["message"], result)
    return result
