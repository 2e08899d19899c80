#!/usr/bin/python3
"""Charts of a `weavelab modes` result folder.

Reads DIR/modes.csv, DIR/mac.csv and DIR/modes.json and writes DIR/modes.png
and .svg: the MAC matrix as a heat map (a row per yarn-level mode, a column per
continuum mode, the chosen pairs marked), and the frequencies of both models
side by side, each yarn mode beside its continuum partner with the pair's MAC.
Several folders (e.g. first guess and calibrated) are drawn as rows of one chart.
A second chart, PREFIX_shapes.png, draws the lowest --shapes yarn-level modes
over the cloth (from DIR/modes_yarn.vtu, DIR/modes_fem.vtu) with their continuum
partners below them: colour the out-of-plane component, arrows the in-plane one.

Usage: plot_modes.py DIR [DIR ...] [--label TEXT ...] [--shapes N] [--out PREFIX]
"""
import argparse
import csv
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "common"))
import runs as wio  # noqa: E402


def read_table(folder, name):
    path = os.path.join(folder, name)
    if not os.path.exists(path):
        wio.fail(f"'{path}' is missing (run `weavelab modes` first)")
    with open(path, newline="", encoding="utf-8") as f:
        return list(csv.DictReader(f))


def draw(folder, label, ax_mac, ax_freq):
    modes = read_table(folder, "modes.csv")
    mac_rows = read_table(folder, "mac.csv")
    columns = [c for c in mac_rows[0] if c.startswith("fem_")]
    mac = [[float(r[c]) for c in columns] for r in mac_rows]
    yarn = [r for r in modes if r["model"] == "yarn"]
    fem = {int(r["mode"]): r for r in modes if r["model"] == "fem"}

    image = ax_mac.imshow(mac, vmin=0, vmax=1, cmap="viridis", origin="upper")
    for r in yarn:
        ax_mac.plot(int(r["paired_mode"]), int(r["mode"]), "s", markerfacecolor="none", markeredgecolor="red",
                    markersize=7)
    ax_mac.set_xlabel("continuum mode", fontsize=8)
    ax_mac.set_ylabel("yarn-level mode", fontsize=8)
    ax_mac.set_title(f"MAC ({label}; red: pairs)", fontsize=9)
    plt.colorbar(image, ax=ax_mac, fraction=0.046)

    index = [int(r["mode"]) for r in yarn]
    ax_freq.plot(index, [float(r["frequency_hz"]) for r in yarn], "o-", label="yarn level")
    ax_freq.plot(range(len(fem)), [float(fem[k]["frequency_hz"]) for k in range(len(fem))], "s--",
                 label="continuum")
    for r in yarn:
        a, f = int(r["mode"]), float(r["paired_frequency_hz"])
        ax_freq.plot([a], [f], "x", color="red")
        ax_freq.annotate(f"{float(r['mac']):.2f}", (a, f), fontsize=6, xytext=(3, -9), textcoords="offset points")
    ax_freq.plot([], [], "x", color="red", label="continuum partner of the yarn mode (MAC)")
    ax_freq.set_xlabel("mode (ascending frequency)", fontsize=8)
    ax_freq.set_ylabel("frequency [Hz]", fontsize=8)
    ax_freq.set_title(f"frequencies ({label})", fontsize=9)
    ax_freq.grid(alpha=0.3)
    ax_freq.legend(fontsize=7)


def draw_shapes(folders, labels, count, path):
    fig, axes = plt.subplots(2 * len(folders), count, figsize=(1.15 * count, 2.7 * len(folders)), squeeze=False)
    for f, folder in enumerate(folders):
        yarn_mesh = wio.read_mesh(os.path.join(folder, "modes_yarn.vtu"))
        fem_mesh = wio.read_mesh(os.path.join(folder, "modes_fem.vtu"))
        rows = {int(r["mode"]): r for r in read_table(folder, "modes.csv") if r["model"] == "yarn"}
        for k in range(min(count, len(rows))):
            r = rows[k]
            partner = int(r["paired_mode"])
            for side, (mesh, mode, title) in enumerate(
                    ((yarn_mesh, k, f"yarn {k}: {float(r['frequency_hz']):.2f} Hz"),
                     (fem_mesh, partner, f"cont. {partner}: {float(r['paired_frequency_hz']):.2f} Hz\n"
                                         f"MAC {float(r['mac']):.2f}"))):
                ax = axes[2 * f + side][k]
                p = mesh.points
                shape = wio.point_array(mesh, f"mode_{mode:02d}")
                ax.scatter(p[:, 0], p[:, 2], c=shape[:, 1], cmap="coolwarm", vmin=-1, vmax=1, s=6, linewidths=0)
                ax.quiver(p[:, 0], p[:, 2], shape[:, 0], shape[:, 2], scale=8, width=0.006)
                ax.set_title(title, fontsize=6)
                ax.set_xticks([])
                ax.set_yticks([])
                ax.set_aspect("equal")
        axes[2 * f][0].set_ylabel(f"yarn level\n({labels[f]})", fontsize=7)
        axes[2 * f + 1][0].set_ylabel(f"continuum\n({labels[f]})", fontsize=7)
    fig.suptitle("Mode shapes over the hanging cloth (colour: out of plane, arrows: in plane)", fontsize=9)
    fig.tight_layout()
    wio.save_figure(fig, path, svg=False)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("folders", nargs="+")
    ap.add_argument("--label", action="append", default=[], help="label per folder (default: its parameters)")
    ap.add_argument("--shapes", type=int, default=8, help="yarn-level modes drawn with their partners (0: none)")
    ap.add_argument("--out", help="output prefix (default FIRST_DIR/modes)")
    a = ap.parse_args()
    if a.label and len(a.label) != len(a.folders):
        wio.fail(f"{len(a.label)} --label for {len(a.folders)} folders")
    fig, axes = plt.subplots(len(a.folders), 2, figsize=(11, 4.2 * len(a.folders)), squeeze=False)
    scene, labels = "", []
    for k, folder in enumerate(a.folders):
        meta_path = os.path.join(folder, "modes.json")
        if not os.path.exists(meta_path):
            wio.fail(f"'{meta_path}' is missing (run `weavelab modes` first)")
        with open(meta_path, encoding="utf-8") as f:
            meta = json.load(f)
        scene = os.path.basename(meta.get("scene", {}).get("file", ""))
        label = a.label[k] if a.label else os.path.basename(meta.get("continuum_parameters", ""))
        labels.append(label)
        draw(folder, label, axes[k][0], axes[k][1])
    fig.suptitle(f"Lowest modes about the hanging equilibrium: {scene}", fontsize=10)
    fig.tight_layout()
    prefix = a.out or os.path.join(a.folders[0], "modes")
    wio.save_figure(fig, f"{prefix}.png")
    print(f"plot_modes.py: wrote {prefix}.png and .svg")
    if a.shapes > 0:
        draw_shapes(a.folders, labels, a.shapes, f"{prefix}_shapes.png")
        print(f"plot_modes.py: wrote {prefix}_shapes.png")


if __name__ == "__main__":
    main()
