#!/usr/bin/env python3
"""Edge curl and course width of free knit patches (the knits study,
experiments/knits/; docs/models.md §11). Usage: plot_knits.py OUT SCENE:RUN [SCENE:RUN ...]

Node k of a knit frame is end k % 2 of contact k // 2, contact = ((r + 1)·wales
+ c)·2 + side for contact rows r = −1 … courses−1 and wales c (the graph's
order, models/knit/knit_graph.cpp). Per frame:
- curl at an edge: the angle [deg] of (mean of the edge row − mean of the row 3
  inside) above the cloth's plane (z up, the face); an edge curling towards the
  face is positive, and the mean of two opposite edges is the curl (a rigid
  tilt of the patch cancels in it, their half difference is that tilt);
- turn at an edge: the angle [deg] of the edge row against the row next to it
  (the edge's own tangent) about the edge, positive towards the face, unwrapped
  over the frames, so that it counts an edge that rolls over: the curl stops at
  ±90° and folds back once the edge has turned past the vertical (frames must
  be close enough for each edge to turn by less than 180° between them); the
  mean of two opposite edges again;
- course width: the mean over the inner contact rows of the row's extent in x;
- intersecting pairs: RUN/self_intersections.csv's count at the frame (pairs of
  yarn pieces that are not neighbours whose capsules overlap, docs/models.md §11.10).
Writes OUT/knits.csv (every frame), OUT/knits_ends.csv (the first and last
frame of each pattern, with the largest count of intersecting pairs over all
frames), OUT/widths.csv (each pattern's course width at the first and last
frame and its ratio to the stockinette's) and OUT/knit_curl.png."""
import os
import sys
import tomllib

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "common"))
import runs as io  # noqa: E402


def angle(v, along):
    return float(np.degrees(np.arctan2(v[2], abs(v[along]))))


def measure(points, courses, wales):
    ids = np.arange(len(points))
    contact = ids // 2
    c = (contact // 2) % wales
    r = contact // 2 // wales - 1
    if r.max() != courses - 1:
        io.fail(f"a frame of {len(points)} points is not a {courses} x {wales} knit")
    mean = lambda sel: points[sel].mean(axis=0)  # noqa: E731
    bottom = angle(mean(r == -1) - mean(r == 2), 1)
    top = angle(mean(r == courses - 1) - mean(r == courses - 4), 1)
    left = angle(mean(c == 0) - mean(c == 3), 0)
    right = angle(mean(c == wales - 1) - mean(c == wales - 4), 0)
    # The edge's tangent against its outward direction in the cloth's plane (wrapped; unwrapped in main).
    tangent = lambda d, along, out: float(np.arctan2(d[2], out * d[along]))  # noqa: E731
    turns = dict(turn_bottom=tangent(mean(r == -1) - mean(r == 0), 1, -1),
                 turn_top=tangent(mean(r == courses - 1) - mean(r == courses - 2), 1, 1),
                 turn_left=tangent(mean(c == 0) - mean(c == 1), 0, -1),
                 turn_right=tangent(mean(c == wales - 1) - mean(c == wales - 2), 0, 1))
    inner = range(1, courses - 2)
    width = np.mean([np.ptp(points[r == k][:, 0]) for k in inner])
    return dict(bottom=bottom, top=top, left=left, right=right, course_curl=(bottom + top) / 2,
                wale_curl=(left + right) / 2, width_mm=1e3 * width, **turns)


def unwrap_turns(series):
    """The edge turns of one run's frames, unwrapped over time, in degrees, and their means."""
    for key in ("turn_bottom", "turn_top", "turn_left", "turn_right"):
        for (_, m), x in zip(series, np.degrees(np.unwrap([m[key] for _, m in series]))):
            m[key] = float(x)
    for _, m in series:
        m["course_turn"] = (m["turn_bottom"] + m["turn_top"]) / 2
        m["wale_turn"] = (m["turn_left"] + m["turn_right"]) / 2


def add_intersections(series, run):
    """Each frame's intersecting pairs (RUN/self_intersections.csv, matched by time) and the largest so far."""
    path = os.path.join(run, "self_intersections.csv")
    if not os.path.exists(path):
        io.fail(f"{path}: missing (every knit run writes it)")
    counts = np.loadtxt(path, delimiter=",", skiprows=1, ndmin=2)
    largest = 0
    for t, m in series:
        near = np.abs(counts[:, 0] - t) <= 1e-9 * max(1.0, abs(t))
        if not near.any():
            io.fail(f"{path}: no count at t = {t}")
        m["intersecting_pairs"] = int(counts[near, 1][0])
        largest = max(largest, m["intersecting_pairs"])
        m["max_intersecting_pairs"] = largest


def widths_table(series):
    """Per pattern: course width [mm] at the first and last frame, and the ratio to the stockinette's."""
    ref = series.get("stockinette")
    lines = ["pattern,width_first_mm,width_last_mm,ratio_to_stockinette_first,ratio_to_stockinette_last"]
    for name, s in series.items():
        first, last = s[0][1]["width_mm"], s[-1][1]["width_mm"]
        ratio = [f"{w / r:.4g}" if ref else "" for w, r in
                 ((first, ref[0][1]["width_mm"] if ref else 1), (last, ref[-1][1]["width_mm"] if ref else 1))]
        lines.append(f"{name},{first:.6g},{last:.6g},{ratio[0]},{ratio[1]}")
    return "\n".join(lines) + "\n"


def main():
    if len(sys.argv) < 3:
        io.fail(__doc__)
    out = sys.argv[1]
    rows, series = [], {}
    for arg in sys.argv[2:]:
        scene_path, run = arg.split(":", 1)
        with open(scene_path, "rb") as f:
            scene = tomllib.load(f)
        p = scene["cloth"]["pattern"]
        name = p["kind"]
        s = [(t, measure(mesh.points, p["courses"], p["wales"])) for t, mesh in io.read_frames(run)]
        unwrap_turns(s)
        add_intersections(s, run)
        rows += [dict(pattern=name, t_s=t, **m) for t, m in s]
        series[name] = s
    keys = ["pattern", "t_s", "bottom", "top", "left", "right", "course_curl", "wale_curl", "width_mm",
            "turn_bottom", "turn_top", "turn_left", "turn_right", "course_turn", "wale_turn", "intersecting_pairs",
            "max_intersecting_pairs"]
    text = ",".join(keys) + "\n" + "".join(
        ",".join(str(r[k]) if k == "pattern" else f"{r[k]:.6g}" for k in keys) + "\n" for r in rows)
    io.write_text_atomically(os.path.join(out, "knits.csv"), text)
    ends = [dict(pattern=name, t_s=t, **m) for name, s in series.items() for t, m in (s[0], s[-1])]
    io.write_text_atomically(os.path.join(out, "knits_ends.csv"), ",".join(keys) + "\n" + "".join(
        ",".join(str(r[k]) if k == "pattern" else f"{r[k]:.6g}" for k in keys) + "\n" for r in ends))
    io.write_text_atomically(os.path.join(out, "widths.csv"), widths_table(series))
    print(f"{'pattern':12s} {'t [s]':>6s} {'course-edge curl':>17s} {'wale-edge curl':>15s} "
          f"{'tilt':>6s} {'course width [mm]':>18s} {'turn: bottom':>13s} {'top':>7s} {'left':>7s} {'right':>7s}")
    for name, s in series.items():
        for t, m in (s[0], s[-1]):
            print(f"{name:12s} {t:6.3f} {m['course_curl']:+16.2f}° {m['wale_curl']:+14.2f}° "
                  f"{(m['left'] - m['right']) / 2:+5.1f}° {m['width_mm']:18.3f} {m['turn_bottom']:+12.1f}° "
                  f"{m['turn_top']:+6.1f}° {m['turn_left']:+6.1f}° {m['turn_right']:+6.1f}°")
    if "rib2x2" in series and "stockinette" in series:
        ratio = series["rib2x2"][-1][1]["width_mm"] / series["stockinette"][-1][1]["width_mm"]
        print(f"course width rib2x2 / stockinette at the last frame: {ratio:.4f}")
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(1, 2, figsize=(9, 3.5))
    for name, s in series.items():
        t = [x[0] for x in s]
        line = ax[0].plot(t, [x[1]["course_curl"] for x in s], label=name)[0]
        ax[0].plot(t, [x[1]["course_turn"] for x in s], "--", color=line.get_color())
        line = ax[1].plot(t, [x[1]["wale_curl"] for x in s], label=name)[0]
        ax[1].plot(t, [x[1]["wale_turn"] for x in s], "--", color=line.get_color())
    ax[0].set_title("course edges (top, bottom): curl, turn dashed", fontsize=9)
    ax[1].set_title("wale edges (left, right): curl, turn dashed", fontsize=9)
    for a in ax:
        a.set_xlabel("t [s]")
        a.set_ylabel("curl [deg]")
        a.legend()
    io.save_figure(fig, os.path.join(out, "knit_curl.png"), svg=False)


if __name__ == "__main__":
    try:
        main()
    except io.RunError as e:
        io.fail(str(e))
