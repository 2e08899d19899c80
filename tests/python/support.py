"""Shared pieces of the Python module's tests (run by ctest: python/CMakeLists.txt)."""
import os
import xml.etree.ElementTree as ET

import numpy as np

SOURCE_DIR = os.environ.get("WEAVELAB_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))
CLI = os.environ.get("WEAVELAB_CLI", os.path.join(SOURCE_DIR, "build", "weavelab"))
HANGING_WIND = os.path.join(SOURCE_DIR, "experiments", "scenes", "hanging_wind.toml")


def small_scene(weavelab, size=7, duration=0.02):
    """The hanging cloth in the wind at size×size crossings, held at its two top corners."""
    scene = weavelab.load_scene(HANGING_WIND)
    scene.update({"cloth.warps": size, "cloth.wefts": size,
                  "handles": [{"node": [0, 0], "stiffness_N_per_m": 1e4},
                              {"node": [size - 1, 0], "stiffness_N_per_m": 1e4}],
                  "time.duration_s": duration, "time.output_interval_s": 0.005})
    return scene


def read_vtu(path):
    """Points and point data of a VTU frame written by the run driver (ASCII,
    %.17g, so float() gives back the very bits)."""
    root = ET.parse(path).getroot()
    piece = root.find("UnstructuredGrid/Piece")

    def values(array):
        return np.array([float(x) for x in array.text.split()])

    out = {"positions": values(piece.find("Points/DataArray")).reshape(-1, 3)}
    for array in piece.findall("PointData/DataArray"):
        n = int(array.get("NumberOfComponents", "1"))
        data = values(array)
        out[array.get("Name")] = data.reshape(-1, n) if n > 1 else data
    return out
