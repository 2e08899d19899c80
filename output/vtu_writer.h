// One output frame as a VTK XML UnstructuredGrid (.vtu), ASCII, full double
// precision, readable by meshio and ParaView (docs/design.md §9).
#pragma once
#include <string>

#include "models/core/frame.h"

namespace wl {

// The .vtu document for `frame`: points, all cell blocks in order (mixed line,
// triangle and quad cells; VTK types from CellType), every point_data and
// cell_data array as Float64 with its NumberOfComponents (omitted for scalars,
// the VTK default 1, so meshio reads them as 1-D arrays). Cell data spans all
// cells of all blocks in block order. Numbers are written with %.17g.
// Throws std::invalid_argument naming the array or block when sizes disagree
// or a connectivity index is out of range.
std::string to_vtu(const Frame& frame);

// XML attribute escaping (&, <, >, ", ') shared by the VTU and PVD writers.
std::string xml_escape(const std::string& text);

}  // namespace wl
