#include "output/vtu_writer.h"

#include <cstdio>
#include <stdexcept>

namespace wl {
namespace {

void append_double(std::string& out, double x) {
  char buf[32];
  const int n = std::snprintf(buf, sizeof buf, "%.17g", x);
  out.append(buf, static_cast<size_t>(n));
}

void append_int(std::string& out, long long x) {
  char buf[24];
  const int n = std::snprintf(buf, sizeof buf, "%lld", x);
  out.append(buf, static_cast<size_t>(n));
}

void check_array(const DataArray& a, long long entries, const char* where) {
  if (a.components < 1)
    throw std::invalid_argument(std::string("to_vtu: ") + where + " array '" + a.name + "' has NumberOfComponents " +
                                std::to_string(a.components) + ", expected >= 1");
  if (static_cast<long long>(a.values.size()) != entries * a.components)
    throw std::invalid_argument(std::string("to_vtu: ") + where + " array '" + a.name + "' has " +
                                std::to_string(a.values.size()) + " values, expected " + std::to_string(entries) +
                                " entries x " + std::to_string(a.components) +
                                " components = " + std::to_string(entries * a.components));
}

void append_data_array(std::string& out, const DataArray& a) {
  out += "        <DataArray type=\"Float64\" Name=\"";
  out += xml_escape(a.name);
  out += '"';
  if (a.components != 1) {  // omitted for scalars (VTK default 1) so meshio reads them as 1-D arrays
    out += " NumberOfComponents=\"";
    append_int(out, a.components);
    out += '"';
  }
  out += " format=\"ascii\">\n";
  for (size_t k = 0; k < a.values.size(); ++k) {
    out += (k % a.components == 0) ? "          " : " ";
    append_double(out, a.values[k]);
    if ((k + 1) % a.components == 0) out += '\n';
  }
  out += "        </DataArray>\n";
}

}  // namespace

std::string xml_escape(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&apos;"; break;
      default: out += c;
    }
  }
  return out;
}

std::string to_vtu(const Frame& frame) {
  const long long n_points = frame.points.rows();
  long long n_cells = 0, n_conn = 0;
  for (size_t b = 0; b < frame.cells.size(); ++b) {
    const CellBlock& block = frame.cells[b];
    const int type = static_cast<int>(block.type);
    if (block.type != CellType::line && block.type != CellType::triangle && block.type != CellType::quad)
      throw std::invalid_argument("to_vtu: cell block " + std::to_string(b) + " has VTK cell type " +
                                  std::to_string(type) + ", expected 3 (line), 5 (triangle) or 9 (quad)");
    const int npc = block.nodes_per_cell();
    if (block.connectivity.size() % npc != 0)
      throw std::invalid_argument("to_vtu: cell block " + std::to_string(b) + " has " +
                                  std::to_string(block.connectivity.size()) +
                                  " connectivity entries, not a multiple of " + std::to_string(npc));
    for (int node : block.connectivity)
      if (node < 0 || node >= n_points)
        throw std::invalid_argument("to_vtu: cell block " + std::to_string(b) + " refers to point " +
                                    std::to_string(node) + ", expected 0.." + std::to_string(n_points - 1));
    n_cells += block.size();
    n_conn += static_cast<long long>(block.connectivity.size());
  }
  for (const DataArray& a : frame.point_data) check_array(a, n_points, "point_data");
  for (const DataArray& a : frame.cell_data) check_array(a, n_cells, "cell_data");

  std::string out;
  size_t numbers = 3 * n_points + 2 * n_conn;
  for (const DataArray& a : frame.point_data) numbers += a.values.size();
  for (const DataArray& a : frame.cell_data) numbers += a.values.size();
  out.reserve(1024 + 25 * numbers);

  out += "<?xml version=\"1.0\"?>\n";
  out += "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n";
  out += "  <UnstructuredGrid>\n";
  out += "    <FieldData>\n";
  out += "      <DataArray type=\"Float64\" Name=\"TimeValue\" NumberOfTuples=\"1\" format=\"ascii\">\n        ";
  append_double(out, frame.time);
  out += "\n      </DataArray>\n";
  out += "    </FieldData>\n";
  out += "    <Piece NumberOfPoints=\"";
  append_int(out, n_points);
  out += "\" NumberOfCells=\"";
  append_int(out, n_cells);
  out += "\">\n";

  out += "      <PointData>\n";
  for (const DataArray& a : frame.point_data) append_data_array(out, a);
  out += "      </PointData>\n";
  out += "      <CellData>\n";
  for (const DataArray& a : frame.cell_data) append_data_array(out, a);
  out += "      </CellData>\n";

  out += "      <Points>\n";
  out += "        <DataArray type=\"Float64\" Name=\"Points\" NumberOfComponents=\"3\" format=\"ascii\">\n";
  for (long long i = 0; i < n_points; ++i) {
    out += "          ";
    append_double(out, frame.points(i, 0));
    out += ' ';
    append_double(out, frame.points(i, 1));
    out += ' ';
    append_double(out, frame.points(i, 2));
    out += '\n';
  }
  out += "        </DataArray>\n";
  out += "      </Points>\n";

  out += "      <Cells>\n";
  out += "        <DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n";
  for (const CellBlock& block : frame.cells) {
    const int npc = block.nodes_per_cell();
    for (size_t k = 0; k < block.connectivity.size(); ++k) {
      out += (k % npc == 0) ? "          " : " ";
      append_int(out, block.connectivity[k]);
      if ((k + 1) % npc == 0) out += '\n';
    }
  }
  out += "        </DataArray>\n";
  out += "        <DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n";
  long long offset = 0;
  for (const CellBlock& block : frame.cells) {
    const int npc = block.nodes_per_cell();
    for (int c = 0; c < block.size(); ++c) {
      offset += npc;
      out += "          ";
      append_int(out, offset);
      out += '\n';
    }
  }
  out += "        </DataArray>\n";
  out += "        <DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n";
  for (const CellBlock& block : frame.cells) {
    const int type = static_cast<int>(block.type);
    for (int c = 0; c < block.size(); ++c) {
      out += "          ";
      append_int(out, type);
      out += '\n';
    }
  }
  out += "        </DataArray>\n";
  out += "      </Cells>\n";
  out += "    </Piece>\n";
  out += "  </UnstructuredGrid>\n";
  out += "</VTKFile>\n";
  return out;
}

}  // namespace wl
