#include "app/vtk_xml.hpp"

#include <algorithm>
#include <bit>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <type_traits>

#include <zlib.h>

namespace fetic::app {
namespace {

// VTK compresses in blocks of this many uncompressed bytes (its writer's default).
constexpr std::size_t kBlockSize = 32768;

template <typename T>
const char* vtk_type();
template <>
const char* vtk_type<double>() {
  return "Float64";
}
template <>
const char* vtk_type<std::int32_t>() {
  return "Int32";
}
template <>
const char* vtk_type<std::uint8_t>() {
  return "UInt8";
}
template <>
const char* vtk_type<std::int64_t>() {
  return "Int64";
}

void append_u64(std::vector<std::uint8_t>& bytes, std::uint64_t value) {
  for (int b = 0; b < 8; ++b)
    bytes.push_back(static_cast<std::uint8_t>(value >> (8 * b)));  // little-endian
}

// The raw bytes of the values, little-endian (the machine's order on x86-64 and arm64).
template <typename T>
std::vector<std::uint8_t> raw_bytes(const std::vector<T>& values) {
  static_assert(std::endian::native == std::endian::little, "big-endian hosts need byte swaps");
  std::vector<std::uint8_t> bytes(values.size() * sizeof(T));
  if (!values.empty()) std::memcpy(bytes.data(), values.data(), bytes.size());
  return bytes;
}

template <typename T>
void write_ascii(std::ostream& out, const std::vector<T>& values) {
  char buffer[40];
  for (std::size_t i = 0; i < values.size(); ++i) {
    if constexpr (std::is_floating_point_v<T>)
      std::snprintf(buffer, sizeof buffer, "%.17g", values[i]);  // reads back exactly
    else
      std::snprintf(buffer, sizeof buffer, "%lld", static_cast<long long>(values[i]));
    out << buffer << ((i + 1) % 6 == 0 || i + 1 == values.size() ? "\n" : " ");
  }
}

// Inline binary: base64 of (UInt64 byte count, data) in one stream.
std::string encode_binary(const std::vector<std::uint8_t>& data) {
  std::vector<std::uint8_t> bytes;
  bytes.reserve(8 + data.size());
  append_u64(bytes, data.size());
  bytes.insert(bytes.end(), data.begin(), data.end());
  return base64(bytes.data(), bytes.size());
}

// Inline compressed: base64 of the header (blocks, block size, last block size, each
// block's compressed size), then base64 of the compressed blocks - two streams, as VTK's
// reader expects for inline data.
std::string encode_zlib(const std::vector<std::uint8_t>& data) {
  const std::size_t blocks = (data.size() + kBlockSize - 1) / kBlockSize;
  std::vector<std::uint8_t> compressed;
  std::vector<std::uint64_t> sizes;
  for (std::size_t b = 0; b < blocks; ++b) {
    const std::size_t size = std::min(kBlockSize, data.size() - b * kBlockSize);
    uLongf length = compressBound(static_cast<uLong>(size));
    std::vector<std::uint8_t> block(length);
    if (compress2(block.data(), &length, data.data() + b * kBlockSize, static_cast<uLong>(size),
                  Z_DEFAULT_COMPRESSION) != Z_OK)
      throw std::runtime_error("zlib could not compress a data array");
    compressed.insert(compressed.end(), block.begin(), block.begin() + length);
    sizes.push_back(length);
  }
  std::vector<std::uint8_t> header;
  append_u64(header, blocks);
  append_u64(header, kBlockSize);
  const std::size_t last = data.size() - (blocks == 0 ? 0 : (blocks - 1) * kBlockSize);
  append_u64(header, blocks == 0 ? 0 : last);
  for (std::uint64_t size : sizes)
    append_u64(header, size);
  return base64(header.data(), header.size()) + base64(compressed.data(), compressed.size());
}

void write_array(std::ostream& out, const VtkArray& array, VtkEncoding encoding,
                 const char* indent) {
  std::visit(
      [&](const auto& values) {
        using T = typename std::decay_t<decltype(values)>::value_type;
        // An empty array is written as ASCII: there is nothing to encode.
        const VtkEncoding used = values.empty() ? VtkEncoding::Ascii : encoding;
        out << indent << "<DataArray type=\"" << vtk_type<T>() << "\" Name=\"" << array.name
            << "\"";
        if (array.components != 1) out << " NumberOfComponents=\"" << array.components << "\"";
        out << " format=\"" << (used == VtkEncoding::Ascii ? "ascii" : "binary") << "\">\n";
        if (used == VtkEncoding::Ascii) {
          write_ascii(out, values);
        } else {
          const auto bytes = raw_bytes(values);
          out << (used == VtkEncoding::Zlib ? encode_zlib(bytes) : encode_binary(bytes)) << '\n';
        }
        out << indent << "</DataArray>\n";
      },
      array.values);
}

// Field data arrays say how many tuples they hold.
void write_field_array(std::ostream& out, const VtkArray& array, VtkEncoding encoding) {
  std::visit(
      [&](const auto& values) {
        using T = typename std::decay_t<decltype(values)>::value_type;
        out << "      <DataArray type=\"" << vtk_type<T>() << "\" Name=\"" << array.name
            << "\" NumberOfTuples=\"" << values.size() / static_cast<std::size_t>(array.components)
            << "\" format=\"ascii\">\n";
        write_ascii(out, values);
        out << "      </DataArray>\n";
      },
      array.values);
  (void)encoding;  // a handful of values: always ASCII, readable in the file
}

// A String array of one value, as VTK's writer stores it in ASCII: each byte's code, then
// a 0 that ends the string.
void write_field_text(std::ostream& out, const std::string& name, const std::string& text) {
  out << "      <Array type=\"String\" Name=\"" << name
      << "\" NumberOfTuples=\"1\" format=\"ascii\">\n        ";
  for (unsigned char c : text)
    out << static_cast<int>(c) << ' ';
  out << "0\n      </Array>\n";
}

void write_data(std::ostream& out, const char* tag, const std::vector<VtkArray>& arrays,
                VtkEncoding encoding) {
  out << "      <" << tag << ">\n";
  for (const VtkArray& array : arrays)
    write_array(out, array, encoding, "        ");
  out << "      </" << tag << ">\n";
}

std::string xml_escape(const std::string& text) {
  std::string result;
  for (char c : text) {
    switch (c) {
      case '&':
        result += "&amp;";
        break;
      case '<':
        result += "&lt;";
        break;
      case '>':
        result += "&gt;";
        break;
      case '"':
        result += "&quot;";
        break;
      default:
        result += c;
    }
  }
  return result;
}

}  // namespace

std::optional<VtkEncoding> parse_vtk_encoding(const std::string& name) {
  if (name == "ascii") return VtkEncoding::Ascii;
  if (name == "binary") return VtkEncoding::Binary;
  if (name == "zlib") return VtkEncoding::Zlib;
  return std::nullopt;
}

std::string base64(const std::uint8_t* data, std::size_t size) {
  static constexpr char alphabet[] =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string text;
  text.reserve((size + 2) / 3 * 4);
  std::size_t i = 0;
  for (; i + 3 <= size; i += 3) {
    const std::uint32_t v = (std::uint32_t{data[i]} << 16) | (std::uint32_t{data[i + 1]} << 8) |
                            std::uint32_t{data[i + 2]};
    text += alphabet[(v >> 18) & 63];
    text += alphabet[(v >> 12) & 63];
    text += alphabet[(v >> 6) & 63];
    text += alphabet[v & 63];
  }
  if (i < size) {
    const bool two = i + 1 < size;
    const std::uint32_t v =
        (std::uint32_t{data[i]} << 16) | (two ? std::uint32_t{data[i + 1]} << 8 : 0u);
    text += alphabet[(v >> 18) & 63];
    text += alphabet[(v >> 12) & 63];
    text += two ? alphabet[(v >> 6) & 63] : '=';
    text += '=';
  }
  return text;
}

void write_vtu(std::ostream& out, const VtkGrid& grid, VtkEncoding encoding) {
  out << "<?xml version=\"1.0\"?>\n"
      << "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
         "header_type=\"UInt64\""
      << (encoding == VtkEncoding::Zlib ? " compressor=\"vtkZLibDataCompressor\"" : "") << ">\n"
      << "  <UnstructuredGrid>\n";
  if (!grid.field_data.empty() || !grid.field_text.empty()) {
    out << "    <FieldData>\n";
    for (const VtkArray& array : grid.field_data)
      write_field_array(out, array, encoding);
    for (const auto& [name, text] : grid.field_text)
      write_field_text(out, name, text);
    out << "    </FieldData>\n";
  }
  out << "    <Piece NumberOfPoints=\"" << grid.points.size() / 3 << "\" NumberOfCells=\""
      << grid.types.size() << "\">\n";
  write_data(out, "PointData", grid.point_data, encoding);
  write_data(out, "CellData", grid.cell_data, encoding);
  write_data(out, "Points", {VtkArray{"Points", 3, grid.points}}, encoding);
  write_data(out, "Cells",
             {VtkArray{"connectivity", 1, grid.connectivity}, VtkArray{"offsets", 1, grid.offsets},
              VtkArray{"types", 1, grid.types}},
             encoding);
  out << "    </Piece>\n"
      << "  </UnstructuredGrid>\n"
      << "</VTKFile>\n";
}

void write_pvd(std::ostream& out, const std::vector<PvdEntry>& entries) {
  out << "<?xml version=\"1.0\"?>\n"
      << "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
      << "  <Collection>\n";
  for (const PvdEntry& entry : entries)
    out << pvd_entry(entry);
  out << kPvdClosing;
}

std::string pvd_entry(const PvdEntry& entry) {
  char time[40];
  std::snprintf(time, sizeof time, "%.17g", entry.time);
  return "    <DataSet timestep=\"" + std::string(time) + "\" group=\"\" part=\"0\" file=\"" +
         xml_escape(entry.file) + "\"/>\n";
}

}  // namespace fetic::app
