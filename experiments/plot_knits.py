#!/usr/bin/env python3
"""Edge curl and course width of free knit patches (experiments/knits.sh,
docs/models.md §11). Usage: plot_knits.py OUT SCENE:RUN [SCENE:RUN ...]

Node k of a knit frame is end k % 2 of contact k // 2, contact = ((r + 1)·wales
+ c)·2 + side for contact rows r = −1 … courses−1 and wales c (the graph's
order, models/knit/knit_graph.cpp). Per frame:
- curl at an edge: the angle [deg] of (mean of the edge row − mean of the row 3
  inside) above the cloth's plane (z up, the face); an edge curling towards the
  face is positive, and the mean of two opposite edges is the curl (a rigid
  tilt of the patch cancels in it, their half difference is that tilt);
- course width: the mean over the inner contact rows of the row's extent in x.
Writes OUT/knits.csv and OUT/knit_curl.png."""
import os
import sys
import tomllib

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import weavelab_io as io  # noqa: E402


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
    inner = range(1, courses - 2)
    width = np.mean([np.ptp(points[r == k][:, 0]) for k in inner])
    return dict(bottom=bottom, top=top, left=left, right=right, course_curl=(bottom + top) / 2,
                wale_curl=(left + right) / 2, width_mm=1e3 * width)


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
        for t, mesh in io.read_frames(run):
            m = measure(mesh.points, p["courses"], p["wales"])
            rows.append(dict(pattern=name, t_s=t, **m))
            series.setdefault(name, []).append((t, m))
    keys = ["pattern", "t_s", "bottom", "top", "left", "right", "course_curl", "wale_curl", "width_mm"]
    text = ",".join(keys) + "\n" + "".join(
        ",".join(str(r[k]) if k == "pattern" else f"{r[k]:.6g}" for k in keys) + "\n" for r in rows)
    io.write_text_atomically(os.path.join(out, "knits.csv"), text)
    print(f"{'pattern':12s} {'t [s]':>6s} {'course-edge curl':>17s} {'wale-edge curl':>15s} "
          f"{'tilt':>6s} {'course width [mm]':>18s}")
    for name, s in series.items():
        for t, m in (s[0], s[-1]):
            print(f"{name:12s} {t:6.3f} {m['course_curl']:+16.2f}° {m['wale_curl']:+14.2f}° "
                  f"{(m['left'] - m['right']) / 2:+5.1f}° {m['width_mm']:18.3f}")
    if "rib2x2" in series and "stockinette" in series:
        ratio = series["rib2x2"][-1][1]["width_mm"] / series["stockinette"][-1][1]["width_mm"]
        print(f"course width rib2x2 / stockinette at the last frame: {ratio:.4f}")
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(1, 2, figsize=(9, 3.5))
    for name, s in series.items():
        t = [x[0] for x in s]
        ax[0].plot(t, [x[1]["course_curl"] for x in s], label=name)
        ax[1].plot(t, [x[1]["wale_curl"] for x in s], label=name)
    ax[0].set_title("curl at the course edges (top, bottom)")
    ax[1].set_title("curl at the wale edges (left, right)")
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
