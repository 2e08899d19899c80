#!/usr/bin/python3
"""Charts of a `weavelab modes` result folder.

Reads DIR/modes.csv, DIR/mac.csv and DIR/modes.json and writes DIR/modes.png
and .svg: the MAC matrix as a heat map (a row per yarn-level mode, a column per
continuum mode, the chosen pairs marked), and the frequencies of both models
side by side, each yarn mode beside its continuum partner with the pair's MAC.
Several folders (e.g. first guess and calibrated) are drawn as rows of one chart.

Usage: plot_modes.py DIR [DIR ...] [--label TEXT ...] [--out PREFIX]
"""
import argparse
import csv
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import weavelab_io as wio  # noqa: E402


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


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("folders", nargs="+")
    ap.add_argument("--label", action="append", default=[], help="label per folder (default: its parameters)")
    ap.add_argument("--out", help="output prefix (default FIRST_DIR/modes)")
    a = ap.parse_args()
    if a.label and len(a.label) != len(a.folders):
        wio.fail(f"{len(a.label)} --label for {len(a.folders)} folders")
    fig, axes = plt.subplots(len(a.folders), 2, figsize=(11, 4.2 * len(a.folders)), squeeze=False)
    scene = ""
    for k, folder in enumerate(a.folders):
        meta_path = os.path.join(folder, "modes.json")
        if not os.path.exists(meta_path):
            wio.fail(f"'{meta_path}' is missing (run `weavelab modes` first)")
        with open(meta_path, encoding="utf-8") as f:
            meta = json.load(f)
        scene = os.path.basename(meta.get("scene", {}).get("file", ""))
        label = a.label[k] if a.label else os.path.basename(meta.get("continuum_parameters", ""))
        draw(folder, label, axes[k][0], axes[k][1])
    fig.suptitle(f"Lowest modes about the hanging equilibrium: {scene}", fontsize=10)
    fig.tight_layout()
    prefix = a.out or os.path.join(a.folders[0], "modes")
    wio.save_figure(fig, f"{prefix}.png")
    print(f"plot_modes.py: wrote {prefix}.png and .svg")


if __name__ == "__main__":
    main()
