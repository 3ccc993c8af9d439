#pragma once
// VTK's XML formats, the part fetic writes: an unstructured grid (.vtu) with point, cell
// and field data, and a collection (.pvd) that makes a time series of them for ParaView.
// Data arrays are written as ASCII, as base64 binary, or as base64 binary of zlib-compressed
// blocks ("vtkZLibDataCompressor"), with UInt64 headers, little-endian - what VTK's own
// writer produces and every VTK reader (ParaView, python3-vtk9, meshio) reads.

#include <cstdint>
#include <functional>
#include <optional>
#include <ostream>
#include <string>
#include <utility>
#include <variant>
#include <vector>

namespace fetic::app {

enum class VtkEncoding { Ascii, Binary, Zlib };

// "ascii", "binary", "zlib".
std::optional<VtkEncoding> parse_vtk_encoding(const std::string& name);

struct VtkArray {
  std::string name;
  int components = 1;
  std::variant<std::vector<double>, std::vector<std::int32_t>, std::vector<std::uint8_t>,
               std::vector<std::int64_t>>
      values;  // components values per tuple
};

struct VtkGrid {
  std::vector<double> points;              // x, y, z per point
  std::vector<std::int64_t> connectivity;  // point indices of every cell, cell after cell
  std::vector<std::int64_t> offsets;       // per cell: end of its points in connectivity
  std::vector<std::uint8_t> types;         // per cell: VTK cell type (3 line, 9 quad)
  std::vector<VtkArray> point_data, cell_data, field_data;
  // Field data strings (VTK String arrays of one tuple): the writer's version, the units.
  std::vector<std::pair<std::string, std::string>> field_text;
};

inline constexpr std::uint8_t kVtkLine = 3;
inline constexpr std::uint8_t kVtkQuad = 9;

// An array made while it is written, a few values at a time (a strut's), so that a large
// grid never exists whole: `make` hands the values, in order, to the sink it is given.
template <typename T>
using VtkSink = std::function<void(const T* values, std::size_t count)>;
struct VtkStreamedArray {
  std::string name;
  int components = 1;
  std::size_t values = 0;  // components per tuple times the tuples, all that make gives
  std::variant<std::function<void(const VtkSink<double>&)>,
               std::function<void(const VtkSink<std::int32_t>&)>,
               std::function<void(const VtkSink<std::uint8_t>&)>,
               std::function<void(const VtkSink<std::int64_t>&)>>
      make;
};
// The array of a VtkArray (which must outlive it), made in one piece.
VtkStreamedArray streamed(const VtkArray& array);

// A grid whose arrays are made as they are written: the same file as write_vtu(VtkGrid).
struct VtkStreamedGrid {
  std::size_t points = 0, cells = 0;
  std::vector<VtkStreamedArray> point_data, cell_data;
  VtkStreamedArray coordinates;  // x, y, z per point
  VtkStreamedArray connectivity, offsets, types;
  std::vector<VtkArray> field_data;
  std::vector<std::pair<std::string, std::string>> field_text;
};

void write_vtu(std::ostream& out, const VtkGrid& grid, VtkEncoding encoding);
// `written` (when given) is called after each array: arrays written, arrays in all.
void write_vtu(std::ostream& out, const VtkStreamedGrid& grid, VtkEncoding encoding,
               const std::function<void(int written, int arrays)>& written = {});

struct PvdEntry {
  double time = 0.0;
  std::string file;  // relative to the .pvd
};
void write_pvd(std::ostream& out, const std::vector<PvdEntry>& entries);
// The parts of a .pvd: one entry's line and the lines that close the file (a series grows
// by overwriting the closing lines with the next entry and them again).
std::string pvd_entry(const PvdEntry& entry);
inline constexpr const char* kPvdClosing = "  </Collection>\n</VTKFile>\n";

// Standard base64 (RFC 4648) with padding.
std::string base64(const std::uint8_t* data, std::size_t size);

}  // namespace fetic::app
