#!/usr/bin/env python3
"""Yarn–yarn contact on the free stockinette (the knits study's `contact` part,
experiments/knits/; docs/models.md §11.10). Usage:
    contact_table.py OUT NAME:SCENE:RUN [NAME:SCENE:RUN ...]

Per run (NAME a label such as "without" or "with", the first the reference):
- intersecting yarn-segment pairs per frame (RUN/self_intersections.csv,
  `intersecting_segment_pairs`): the largest over the frames and the number of
  frames with any;
- the edge turns at the last frame (plot_knits.py's turn: the edge row against
  the row next to it, unwrapped over the frames, towards the face positive), per
  edge, in degrees;
- the steps and the median wall time of a step (RUN/metrics.csv `step_wall_s`,
  the rows after t = 0), and its ratio to the first run's.
Writes OUT/contact.csv and prints it as a table."""
import csv
import os
import statistics
import sys
import tomllib

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "common"))
import runs as io  # noqa: E402
from plot_knits import measure, unwrap_turns  # noqa: E402


def read_csv(path):
    if not os.path.exists(path):
        io.fail(f"{path}: missing (expected a knit run's output)")
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def one_run(name, scene_path, run):
    with open(scene_path, "rb") as f:
        p = tomllib.load(f)["cloth"]["pattern"]
    s = [(t, measure(mesh.points, p["courses"], p["wales"])) for t, mesh in io.read_frames(run)]
    if not s:
        io.fail(f"{run}: no frames")
    unwrap_turns(s)
    t_last, last = s[-1]
    counts = [int(float(r["intersecting_segment_pairs"])) for r in read_csv(os.path.join(run, "self_intersections.csv"))]
    walls = [float(r["step_wall_s"]) for r in read_csv(os.path.join(run, "metrics.csv"))[1:]]
    if not walls:
        io.fail(f"{run}/metrics.csv: no step")
    return dict(run=name, t_s=t_last, max_intersecting_pairs=max(counts),
                frames_with_intersections=sum(c > 0 for c in counts), frames=len(counts),
                turn_bottom=last["turn_bottom"], turn_top=last["turn_top"], turn_left=last["turn_left"],
                turn_right=last["turn_right"], steps=len(walls), median_step_s=statistics.median(walls))


def main():
    if len(sys.argv) < 3:
        io.fail(__doc__)
    out = sys.argv[1]
    rows = []
    for arg in sys.argv[2:]:
        parts = arg.split(":", 2)
        if len(parts) != 3:
            io.fail(f"'{arg}': expected NAME:SCENE:RUN")
        rows.append(one_run(*parts))
    for r in rows:
        r["step_ratio"] = r["median_step_s"] / rows[0]["median_step_s"]
    keys = ["run", "t_s", "max_intersecting_pairs", "frames_with_intersections", "frames", "turn_bottom", "turn_top",
            "turn_left", "turn_right", "steps", "median_step_s", "step_ratio"]
    fmt = lambda v: v if isinstance(v, str) else str(v) if isinstance(v, int) else f"{v:.4g}"  # noqa: E731
    text = ",".join(keys) + "\n" + "".join(",".join(fmt(r[k]) for k in keys) + "\n" for r in rows)
    os.makedirs(out, exist_ok=True)
    io.write_text_atomically(os.path.join(out, "contact.csv"), text)
    print(text, end="")


if __name__ == "__main__":
    try:
        main()
    except io.RunError as e:
        io.fail(str(e))
