#include "python/bindings/frames.h"

#include <stdexcept>

#include <pybind11/numpy.h>

namespace py = pybind11;

namespace wl::python {
namespace {

py::array_t<double> array_of(const std::vector<double>& values, std::vector<py::ssize_t> shape) {
  py::array_t<double> a(shape);
  std::copy(values.begin(), values.end(), a.mutable_data());
  return a;
}

const char* cell_name(CellType t) {
  return t == CellType::line ? "line" : t == CellType::triangle ? "triangle" : "quad";
}

// positions, velocities and every other point data array of frames stacked
// `frames` deep (frames < 0: one frame, no frame axis).
void add_arrays(py::dict& out, long frames, long nodes, const std::vector<double>& points,
                const std::vector<DataArray>& data, const std::vector<CellBlock>& cells) {
  auto shape = [&](int components) {
    std::vector<py::ssize_t> s;
    if (frames >= 0) s.push_back(frames);
    s.push_back(nodes);
    if (components > 1) s.push_back(components);
    return s;
  };
  out["positions"] = array_of(points, shape(3));
  for (const DataArray& d : data)
    out[py::str(d.name == "velocity" ? "velocities" : d.name)] = array_of(d.values, shape(d.components));
  py::dict c;
  for (const CellBlock& b : cells) {
    py::array_t<int> a({static_cast<py::ssize_t>(b.size()), static_cast<py::ssize_t>(b.nodes_per_cell())});
    std::copy(b.connectivity.begin(), b.connectivity.end(), a.mutable_data());
    c[cell_name(b.type)] = a;
  }
  out["cells"] = c;
}

}  // namespace

void FrameStack::add(const Frame& f) {
  if (times_.empty()) {
    nodes_ = f.points.rows();
    cells_ = f.cells;
    for (const DataArray& d : f.point_data) data_.push_back({d.name, d.components, {}});
  }
  if (f.points.rows() != nodes_ || f.point_data.size() != data_.size())
    throw std::logic_error("frames of one run differ in their nodes or point data");
  times_.push_back(f.time);
  points_.insert(points_.end(), f.points.data(), f.points.data() + f.points.size());
  for (size_t k = 0; k < data_.size(); ++k)
    data_[k].values.insert(data_[k].values.end(), f.point_data[k].values.begin(), f.point_data[k].values.end());
}

py::dict FrameStack::arrays() const {
  py::dict out;
  out["time"] = array_of(times_, {static_cast<py::ssize_t>(times_.size())});
  add_arrays(out, size(), nodes_, points_, data_, cells_);
  return out;
}

py::dict frame_arrays(const Frame& f) {
  py::dict out;
  out["time"] = f.time;
  add_arrays(out, -1, f.points.rows(), std::vector<double>(f.points.data(), f.points.data() + f.points.size()),
             f.point_data, f.cells);
  return out;
}

}  // namespace wl::python
