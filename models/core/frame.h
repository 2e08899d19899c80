// What a model hands to the output writers for one frame: points, cells and
// named point/cell data. Writers never see model or integrator internals.
#pragma once
#include <string>
#include <vector>

#include <Eigen/Core>

namespace wl {

enum class CellType : int { line = 3, triangle = 5, quad = 9 };  // VTK cell type ids

struct CellBlock {
  CellType type;
  std::vector<int> connectivity;  // nodes per cell × cells, flat
  int nodes_per_cell() const { return type == CellType::line ? 2 : type == CellType::triangle ? 3 : 4; }
  int size() const { return static_cast<int>(connectivity.size()) / nodes_per_cell(); }
};

struct DataArray {
  std::string name;
  int components = 1;
  std::vector<double> values;  // components × entries, flat
};

struct Frame {
  double time = 0.0;
  Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> points;
  std::vector<CellBlock> cells;
  std::vector<DataArray> point_data;  // one entry per point
  std::vector<DataArray> cell_data;   // one entry per cell, over all blocks in order
};

}  // namespace wl
