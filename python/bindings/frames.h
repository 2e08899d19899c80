// Output frames as numpy arrays: the points and every point data array of a
// series of frames stacked along a first axis (frames × nodes × components).
#pragma once
#include <string>
#include <vector>

#include <pybind11/pybind11.h>

#include "models/core/frame.h"

namespace wl::python {

class FrameStack {
 public:
  // Keeps the frame's time, points and point data (the cells of the first frame only).
  void add(const Frame& f);
  int size() const { return static_cast<int>(times_.size()); }
  // {"time": (F,), "positions": (F, N, 3), "velocities": (F, N, 3) when the
  //  frames carry "velocity", "<name>": (F, N) or (F, N, components) for every
  //  other point data array, "cells": {"line"|"triangle"|"quad": (cells, k)}}.
  pybind11::dict arrays() const;

 private:
  std::vector<double> times_;
  std::vector<double> points_;   // F × N × 3
  std::vector<DataArray> data_;  // per name: F × entries, appended
  std::vector<CellBlock> cells_;
  long nodes_ = 0;
};

// One frame as the same dict (no leading frame axis).
pybind11::dict frame_arrays(const Frame& f);

}  // namespace wl::python
