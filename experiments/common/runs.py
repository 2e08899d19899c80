"""Reading weavelab run folders (docs/design.md §8: results/<name>/).

A run folder holds
  summary.json        run summary (scene, model, integrator, statistics, git, machine)
  metrics.csv         one row per step (time_s, kinetic_J, potential_J, ...);
                      metrics.csv.part while running or after an interrupted run
  <name>.pvd          the frame series, listing frames/<name>_00000.vtu, ...

Only numpy, meshio and the standard library are used. Every reader raises
RunError with the offending path; scripts turn it into a message and exit 2.
"""
import csv
import json
import os
import sys
import xml.etree.ElementTree as ET

import numpy as np


class RunError(Exception):
    """A run folder or one of its files is missing or malformed."""


def fail(message, code=2):
    """Print `message` on stderr as the script's error and exit with `code`."""
    prog = os.path.basename(sys.argv[0]) if sys.argv and sys.argv[0] else "weavelab"
    print(f"{prog}: error: {message}", file=sys.stderr)
    sys.exit(code)


def run_dir(path):
    """`path` as a run folder, or RunError if it is not a folder."""
    if not os.path.isdir(path):
        raise RunError(f"run folder '{path}' does not exist" if not os.path.exists(path)
                       else f"'{path}' is not a folder (expected a run folder)")
    return path


def read_summary(run, required=False):
    """summary.json as a dict; None when absent and not `required`."""
    path = os.path.join(run_dir(run), "summary.json")
    if not os.path.exists(path):
        if required:
            raise RunError(f"'{path}' is missing (every run writes its summary there)")
        return None
    try:
        with open(path, encoding="utf-8") as f:
            return json.load(f)
    except (OSError, ValueError) as e:
        raise RunError(f"cannot read '{path}': {e}") from e


def read_metrics(run, allow_partial=False):
    """metrics.csv as {column: float array}. With `allow_partial`, an interrupted
    run's metrics.csv.part is read when metrics.csv is absent."""
    path = os.path.join(run_dir(run), "metrics.csv")
    if not os.path.exists(path):
        part = path + ".part"
        if allow_partial and os.path.exists(part):
            path = part
        elif os.path.exists(part):
            raise RunError(f"'{path}' is missing but '{part}' exists: the run did not finish")
        else:
            raise RunError(f"'{path}' is missing")
    try:
        with open(path, newline="", encoding="utf-8") as f:
            rows = list(csv.reader(f))
    except OSError as e:
        raise RunError(f"cannot read '{path}': {e}") from e
    if not rows:
        raise RunError(f"'{path}' is empty (expected a header line)")
    header = [h.strip() for h in rows[0]]
    body = [r for r in rows[1:] if r]
    if allow_partial and body and len(body[-1]) != len(header):
        body = body[:-1]  # a torn last row of an interrupted run
    columns = {h: [] for h in header}
    for line, r in enumerate(body, start=2):
        if len(r) != len(header):
            raise RunError(f"'{path}' line {line}: {len(r)} values, expected {len(header)} ({','.join(header)})")
        for h, value in zip(header, r):
            try:
                columns[h].append(float(value))
            except ValueError:
                raise RunError(f"'{path}' line {line}, column '{h}': '{value}' is not a number") from None
    return {h: np.asarray(v, dtype=float) for h, v in columns.items()}


def metric(metrics, column, run="run"):
    """One metrics column, or RunError naming the columns present."""
    if column not in metrics:
        raise RunError(f"{run}: metrics.csv has no column '{column}' (columns: {', '.join(metrics)})")
    return metrics[column]


def step_wall_times(metrics, run="run"):
    """Wall time of every step [s]: the "step_wall_s" column without the row of
    the initial state (the driver's first row, at the start time with 0 s)."""
    wall = metric(metrics, "step_wall_s", run)
    if len(wall) and wall[0] == 0.0:
        wall = wall[1:]
    return wall


def find_pvd(run, name=None):
    """The run's .pvd: <name>.pvd, or the only .pvd in the folder besides the
    obstacles' series (obstacles.pvd, docs/models.md §3.11.5)."""
    run = run_dir(run)
    if name is not None:
        path = os.path.join(run, name if name.endswith(".pvd") else name + ".pvd")
        if not os.path.exists(path):
            raise RunError(f"'{path}' is missing")
        return path
    found = sorted(f for f in os.listdir(run) if f.endswith(".pvd") and f != "obstacles.pvd")
    if not found:
        raise RunError(f"run folder '{run}' holds no .pvd frame series")
    if len(found) > 1:
        raise RunError(f"run folder '{run}' holds several series ({', '.join(found)}); name one")
    return os.path.join(run, found[0])


def read_pvd(pvd):
    """[(time, absolute .vtu path)] in the order listed, checking each file exists."""
    try:
        root = ET.parse(pvd).getroot()
    except (OSError, ET.ParseError) as e:
        raise RunError(f"cannot read '{pvd}': {e}") from e
    collection = root.find("Collection")
    if root.get("type") != "Collection" or collection is None:
        raise RunError(f"'{pvd}' is not a VTK Collection file")
    base = os.path.dirname(os.path.abspath(pvd))
    entries = []
    for k, ds in enumerate(collection.findall("DataSet")):
        file, step = ds.get("file"), ds.get("timestep")
        if file is None or step is None:
            raise RunError(f"'{pvd}': DataSet {k} lacks 'file' or 'timestep'")
        path = file if os.path.isabs(file) else os.path.join(base, file)
        if not os.path.exists(path):
            raise RunError(f"'{pvd}': frame {k} file '{path}' is missing")
        entries.append((float(step), path))
    return entries


def read_mesh(path):
    import meshio
    try:
        return meshio.read(path)
    except Exception as e:  # meshio raises assorted errors on bad files
        raise RunError(f"cannot read '{path}': {e}") from e


def read_frames(run, name=None):
    """[(time, meshio.Mesh)] of the run's series, in time order."""
    return [(t, read_mesh(p)) for t, p in read_pvd(find_pvd(run, name))]


def read_run(run, name=None, allow_partial=False):
    """Everything of a run: {'dir', 'summary' (dict or None), 'metrics', 'frames'}."""
    return {
        "dir": run_dir(run),
        "summary": read_summary(run),
        "metrics": read_metrics(run, allow_partial=allow_partial),
        "frames": read_frames(run, name),
    }


def run_label(run, summary=None):
    """A short name for a run: the summary's scene name (with model and integrator
    when given), else the folder name."""
    if summary is None:
        summary = read_summary(run)
    label = os.path.basename(os.path.normpath(run))
    if isinstance(summary, dict):
        scene = summary.get("scene")
        if isinstance(scene, dict):
            scene = scene.get("name")
        parts = [str(scene)] if scene else [label]
        for key in ("model", "integrator"):
            value = summary.get(key)
            if isinstance(value, dict):
                value = value.get("name")
            if isinstance(value, str) and value:
                parts.append(value)
        label = parts[0] + (f" ({', '.join(parts[1:])})" if len(parts) > 1 else "")
    return label


def point_array(mesh, name, path="mesh"):
    if name not in mesh.point_data:
        raise RunError(f"{path}: no point data '{name}' (present: {', '.join(mesh.point_data) or 'none'})")
    return np.asarray(mesh.point_data[name], dtype=float)


def material_coordinates(mesh, path="mesh"):
    """(n, 2) material (u, v) of every point: point data 'uv', else 'u' and 'v'."""
    if "uv" in mesh.point_data:
        uv = point_array(mesh, "uv", path)
        if uv.ndim != 2 or uv.shape[1] < 2:
            raise RunError(f"{path}: point data 'uv' has shape {uv.shape}, expected (points, 2)")
        return uv[:, :2]
    if "u" in mesh.point_data and "v" in mesh.point_data:
        return np.column_stack([point_array(mesh, "u", path).reshape(-1), point_array(mesh, "v", path).reshape(-1)])
    raise RunError(f"{path}: no material coordinates (point data 'uv', or 'u' and 'v'); "
                   f"present: {', '.join(mesh.point_data) or 'none'}")


def cells_with_data(mesh, cell_type, name=None, path="mesh"):
    """Connectivity of all `cell_type` cells (k, nodes), and with `name` the
    matching cell data rows (k,) or (k, components)."""
    conn, data = [], []
    if name is not None and name not in mesh.cell_data:
        raise RunError(f"{path}: no cell data '{name}' (present: {', '.join(mesh.cell_data) or 'none'})")
    for b, block in enumerate(mesh.cells):
        if block.type == cell_type:
            conn.append(np.asarray(block.data))
            if name is not None:
                data.append(np.asarray(mesh.cell_data[name][b], dtype=float))
    nodes = {"line": 2, "triangle": 3, "quad": 4}.get(cell_type, 0)
    conn = np.concatenate(conn) if conn else np.zeros((0, nodes), dtype=int)
    if name is None:
        return conn
    return conn, (np.concatenate(data) if data else np.zeros((0,)))


def write_text_atomically(path, text):
    """Write `text` to a temporary file beside `path`, then rename it."""
    folder = os.path.dirname(os.path.abspath(path))
    if not os.path.isdir(folder):
        raise RunError(f"cannot write '{path}': folder '{folder}' does not exist")
    tmp = f"{path}.tmp-{os.getpid()}"
    try:
        with open(tmp, "w", encoding="utf-8", newline="") as f:
            f.write(text)
            f.flush()
            os.fsync(f.fileno())
        os.replace(tmp, path)
    except OSError as e:
        if os.path.exists(tmp):
            os.remove(tmp)
        raise RunError(f"cannot write '{path}': {e}") from e


def save_figure(fig, png_path, svg=True):
    """Save `fig` as PNG (and SVG beside it with `svg`) via temporary names."""
    folder = os.path.dirname(os.path.abspath(png_path))
    if not os.path.isdir(folder):
        raise RunError(f"cannot write '{png_path}': folder '{folder}' does not exist")
    root, ext = os.path.splitext(png_path)
    targets = [(png_path, "png")] + ([(root + ".svg", "svg")] if svg else [])
    for target, fmt in targets:
        tmp = f"{target}.tmp-{os.getpid()}"
        try:
            fig.savefig(tmp, format=fmt, dpi=150, bbox_inches="tight")
            os.replace(tmp, target)
        except OSError as e:
            if os.path.exists(tmp):
                os.remove(tmp)
            raise RunError(f"cannot write '{target}': {e}") from e
    return [t for t, _ in targets]
