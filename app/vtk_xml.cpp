#include "app/vtk_xml.hpp"

#include <algorithm>
#include <bit>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <type_traits>

#include <zlib.h>

#include "solver/huge_pages.hpp"
#include "solver/threads.hpp"

namespace fetic::app {
namespace {

// VTK compresses in blocks of this many uncompressed bytes (its writer's default).
constexpr std::size_t kBlockSize = 32768;

// Where a file's compressed blocks wait for their array's end (see write_vtu): reserved
// once at the largest array's bound and only written pages become resident, in huge
// pages (solver/huge_pages.hpp): each 4 KiB page first touched costs a fault of 10-30 us
// on this kind of machine (a microVM), a 2 MiB page about 0.5 us per 4 KiB
// (docs/BENCHMARKS.md, "Page faults").
using Room = solver::huge_pages::Vector<std::uint8_t>;

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

static_assert(std::endian::native == std::endian::little, "big-endian hosts need byte swaps");

// Appends `size` bytes to `buffer` in pieces that fill it to `chunk` bytes, calling
// `full()` (which empties it) each time it is full.
template <class Full>
void append_in_chunks(std::vector<std::uint8_t>& buffer, std::size_t chunk,
                      const std::uint8_t* data, std::size_t size, Full full) {
  while (size > 0) {
    const std::size_t take = std::min(size, chunk - buffer.size());
    buffer.insert(buffer.end(), data, data + take);
    data += take;
    size -= take;
    if (buffer.size() == chunk) full();
  }
}

std::size_t base64_size(std::size_t bytes) {
  return (bytes + 2) / 3 * 4;
}

// Standard base64 of `size` bytes into `text` (base64_size(size) characters).
void encode_base64(const std::uint8_t* data, std::size_t size, char* text) {
  static constexpr char alphabet[] =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::size_t i = 0;
  for (; i + 3 <= size; i += 3, text += 4) {
    const std::uint32_t v = (std::uint32_t{data[i]} << 16) | (std::uint32_t{data[i + 1]} << 8) |
                            std::uint32_t{data[i + 2]};
    text[0] = alphabet[(v >> 18) & 63];
    text[1] = alphabet[(v >> 12) & 63];
    text[2] = alphabet[(v >> 6) & 63];
    text[3] = alphabet[v & 63];
  }
  if (i < size) {
    const bool two = i + 1 < size;
    const std::uint32_t v =
        (std::uint32_t{data[i]} << 16) | (two ? std::uint32_t{data[i + 1]} << 8 : 0u);
    text[0] = alphabet[(v >> 18) & 63];
    text[1] = alphabet[(v >> 12) & 63];
    text[2] = two ? alphabet[(v >> 6) & 63] : '=';
    text[3] = '=';
  }
}

// Base64 of a byte stream handed over in pieces: one encoding, padded only at its end.
// Whole chunks are encoded straight from the bytes given, without a copy into the
// buffer first (a frame's compressed arrays, 477 MB at 1e7 unknowns, pass through here).
class Base64Writer {
 public:
  explicit Base64Writer(std::ostream& out) : out_(out) { buffer_.reserve(kChunk); }
  void write(const std::uint8_t* data, std::size_t size) {
    for (; buffer_.empty() && size >= kChunk; data += kChunk, size -= kChunk)
      put(data, kChunk);
    append_in_chunks(buffer_, kChunk, data, size, [this] { flush(); });
  }
  void flush() {  // whole groups of 3 bytes until the end: no padding in between
    put(buffer_.data(), buffer_.size());
    buffer_.clear();
  }

 private:
  static constexpr std::size_t kChunk = 3 * 16384;
  void put(const std::uint8_t* data, std::size_t size) {
    text_.resize(base64_size(size));
    encode_base64(data, size, text_.data());
    out_.write(text_.data(), static_cast<std::streamsize>(text_.size()));
  }
  std::ostream& out_;
  std::vector<std::uint8_t> buffer_;
  std::string text_;  // the encoded chunk, its room kept from one to the next
};

// Inline compressed: base64 of the header (blocks, block size, last block size, each
// block's compressed size), then base64 of the compressed blocks - two streams, as VTK's
// reader expects for inline data. The header needs every block's size, so the compressed
// blocks of one array are held until its end (not the array itself). Blocks are
// compressed kBatch at a time on the process' threads, each alone (the bytes do not
// depend on the threads), at zlib's fastest level: on a result's float arrays level 1
// compressed 4.8 times faster than the default level 6 to files 1.4% larger (level 6 was
// most of writing a 1e7-unknown result: 47 s of a 60 s target on a loaded machine).
// An array whose first block level 1 cannot shrink below kStoreAbove of its size is
// stored (zlib level 0: the same zlib streams, copied instead of searched): a plane
// result's stresses shrink only to 0.86-0.93 at 27-33 MB/s, where storing runs at GB/s -
// they were 60% of the compressing time for 5% of the file (docs/BENCHMARKS.md, "Outputs
// at 1e7"). Which level an array gets depends on its values alone, not on the threads.
class ZlibBlocks {
 public:
  // `bytes`: the array's size. Room for its compressed blocks is reserved at once (only
  // the pages written become resident): a held array grown by doubling was copied at each
  // step and, at the last one, held twice - the 1e7 displacements' 140 MB among them.
  // `held` is that room, kept from array to array of a file (write_vtu).
  ZlibBlocks(std::size_t bytes, Room& held) : compressed_(held) {
    compressed_.clear();
    compressed_.reserve(room(bytes));
    pending_.reserve(std::min(bytes, kBatch * kBlockSize));  // a batch, not grown by doubling
  }
  // The room the compressed blocks of `bytes` bytes may take.
  static std::size_t room(std::size_t bytes) {
    const std::size_t blocks = (bytes + kBlockSize - 1) / kBlockSize;
    return blocks * compressBound(static_cast<uLong>(kBlockSize));
  }
  void write(const std::uint8_t* data, std::size_t size) {
    append_in_chunks(pending_, kBatch * kBlockSize, data, size, [this] { compress_pending(); });
  }
  void finish(std::ostream& out) {
    if (!pending_.empty()) compress_pending();
    std::vector<std::uint8_t> header;
    append_u64(header, sizes_.size());
    append_u64(header, kBlockSize);
    append_u64(header, last_);
    for (std::uint64_t size : sizes_)
      append_u64(header, size);
    out << base64(header.data(), header.size());
    Base64Writer text(out);
    text.write(compressed_.data(), compressed_.size());
    text.flush();
  }

 private:
  static constexpr std::size_t kBatch = 64;  // 2 MB of values: enough for two threads

  static constexpr double kStoreAbove = 0.75;

  // Level 1, or 0 when the array's first block does not shrink below kStoreAbove.
  void choose_level() {
    const std::size_t size = std::min(kBlockSize, pending_.size());
    uLongf length = compressBound(static_cast<uLong>(size));
    std::vector<std::uint8_t> probe(length);
    const bool shrinks = compress2(probe.data(), &length, pending_.data(), static_cast<uLong>(size),
                                   Z_BEST_SPEED) == Z_OK &&
                         static_cast<double>(length) <= kStoreAbove * static_cast<double>(size);
    level_ = shrinks ? Z_BEST_SPEED : Z_NO_COMPRESSION;
  }

  void compress_pending() {
    if (level_ < 0) choose_level();
    const std::size_t blocks = (pending_.size() + kBlockSize - 1) / kBlockSize;
    std::vector<std::vector<std::uint8_t>> out(blocks);
    bool failed = false;
    const int threads = solver::threads_for(static_cast<long long>(blocks) * kWorkPerBlock);
#pragma omp parallel for num_threads(threads) schedule(dynamic) reduction(|| : failed)
    for (std::size_t b = 0; b < blocks; ++b) {
      const std::size_t from = b * kBlockSize;
      const std::size_t size = std::min(kBlockSize, pending_.size() - from);
      uLongf length = compressBound(static_cast<uLong>(size));
      out[b].resize(length);
      failed = failed || compress2(out[b].data(), &length, pending_.data() + from,
                                   static_cast<uLong>(size), level_) != Z_OK;
      out[b].resize(length);
    }
    if (failed) throw std::runtime_error("zlib could not compress a data array");
    for (const std::vector<std::uint8_t>& block : out) {
      compressed_.insert(compressed_.end(), block.begin(), block.end());
      sizes_.push_back(block.size());
    }
    last_ = pending_.size() - (blocks - 1) * kBlockSize;
    pending_.clear();
  }
  // A block takes about a millisecond to compress (threads.hpp counts microseconds).
  static constexpr long long kWorkPerBlock = 1000;
  std::vector<std::uint8_t> pending_;
  Room& compressed_;
  std::vector<std::uint64_t> sizes_;
  std::uint64_t last_ = 0;
  int level_ = -1;  // not chosen yet
};

template <typename T>
void write_ascii_value(std::ostream& out, T value, bool line_end) {
  char buffer[40];
  if constexpr (std::is_floating_point_v<T>)
    std::snprintf(buffer, sizeof buffer, "%.17g", value);  // reads back exactly
  else
    std::snprintf(buffer, sizeof buffer, "%lld", static_cast<long long>(value));
  out << buffer << (line_end ? "\n" : " ");
}

template <typename T>
void write_ascii(std::ostream& out, const std::vector<T>& values) {
  for (std::size_t i = 0; i < values.size(); ++i)
    write_ascii_value(out, values[i], (i + 1) % 6 == 0 || i + 1 == values.size());
}

// The values `make` gives, encoded; throws std::logic_error unless they are `count`.
template <typename T>
void write_values(std::ostream& out, const std::function<void(const VtkSink<T>&)>& make,
                  std::size_t count, VtkEncoding encoding, Room& held) {
  std::size_t made = 0;
  if (encoding == VtkEncoding::Ascii) {
    make([&](const T* values, std::size_t n) {
      for (std::size_t k = 0; k < n; ++k, ++made)
        write_ascii_value(out, values[k], (made + 1) % 6 == 0 || made + 1 == count);
    });
  } else if (encoding == VtkEncoding::Binary) {
    // Inline binary: base64 of (UInt64 byte count, data) in one stream.
    Base64Writer text(out);
    std::vector<std::uint8_t> header;
    append_u64(header, count * sizeof(T));
    text.write(header.data(), header.size());
    make([&](const T* values, std::size_t n) {
      text.write(reinterpret_cast<const std::uint8_t*>(values), n * sizeof(T));
      made += n;
    });
    text.flush();
    out << '\n';
  } else {
    ZlibBlocks blocks(count * sizeof(T), held);
    make([&](const T* values, std::size_t n) {
      blocks.write(reinterpret_cast<const std::uint8_t*>(values), n * sizeof(T));
      made += n;
    });
    blocks.finish(out);
    out << '\n';
  }
  if (made != count) throw std::logic_error("a VTK array made another count than announced");
}

// The value type of an array's maker.
template <typename Maker>
struct MakerValue;
template <typename T>
struct MakerValue<std::function<void(const VtkSink<T>&)>> {
  using type = T;
};

void write_array(std::ostream& out, const VtkStreamedArray& array, VtkEncoding encoding,
                 const char* indent, Room& held) {
  std::visit(
      [&](const auto& make) {
        using T = typename MakerValue<std::decay_t<decltype(make)>>::type;
        // An empty array is written as ASCII: there is nothing to encode.
        const VtkEncoding used = array.values == 0 ? VtkEncoding::Ascii : encoding;
        out << indent << "<DataArray type=\"" << vtk_type<T>() << "\" Name=\"" << array.name
            << "\"";
        if (array.components != 1) out << " NumberOfComponents=\"" << array.components << "\"";
        out << " format=\"" << (used == VtkEncoding::Ascii ? "ascii" : "binary") << "\">\n";
        write_values<T>(out, make, array.values, used, held);
        out << indent << "</DataArray>\n";
      },
      array.make);
}

template <typename T>
VtkStreamedArray streamed_vector(const std::string& name, int components,
                                 const std::vector<T>& values) {
  VtkStreamedArray array{name, components, values.size(), {}};
  array.make = std::function<void(const VtkSink<T>&)>(
      [&values](const VtkSink<T>& put) { put(values.data(), values.size()); });
  return array;
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

// `done` counts the arrays written.
void write_data(std::ostream& out, const char* tag, const std::vector<VtkStreamedArray>& arrays,
                VtkEncoding encoding, Room& held, const std::function<void()>& done) {
  out << "      <" << tag << ">\n";
  for (const VtkStreamedArray& array : arrays) {
    write_array(out, array, encoding, "        ", held);
    done();
  }
  out << "      </" << tag << ">\n";
}

// The room ZlibBlocks needs for the largest array of the grid.
std::size_t largest_room(const VtkStreamedGrid& grid) {
  std::size_t largest = 0;
  const auto take = [&](const VtkStreamedArray& array) {
    std::visit(
        [&](const auto& make) {
          using T = typename MakerValue<std::decay_t<decltype(make)>>::type;
          largest = std::max(largest, ZlibBlocks::room(array.values * sizeof(T)));
        },
        array.make);
  };
  for (const std::vector<VtkStreamedArray>* arrays : {&grid.point_data, &grid.cell_data})
    for (const VtkStreamedArray& array : *arrays)
      take(array);
  for (const VtkStreamedArray* array :
       {&grid.coordinates, &grid.connectivity, &grid.offsets, &grid.types})
    take(*array);
  return largest;
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
  std::string text(base64_size(size), '\0');
  encode_base64(data, size, text.data());
  return text;
}

VtkStreamedArray streamed(const VtkArray& array) {
  return std::visit(
      [&](const auto& values) { return streamed_vector(array.name, array.components, values); },
      array.values);
}

void write_vtu(std::ostream& out, const VtkGrid& grid, VtkEncoding encoding) {
  VtkStreamedGrid whole;
  whole.points = grid.points.size() / 3;
  whole.cells = grid.types.size();
  for (const VtkArray& array : grid.point_data)
    whole.point_data.push_back(streamed(array));
  for (const VtkArray& array : grid.cell_data)
    whole.cell_data.push_back(streamed(array));
  whole.coordinates = streamed_vector("Points", 3, grid.points);
  whole.connectivity = streamed_vector("connectivity", 1, grid.connectivity);
  whole.offsets = streamed_vector("offsets", 1, grid.offsets);
  whole.types = streamed_vector("types", 1, grid.types);
  whole.field_data = grid.field_data;
  whole.field_text = grid.field_text;
  write_vtu(out, whole, encoding);
}

void write_vtu(std::ostream& out, const VtkStreamedGrid& grid, VtkEncoding encoding,
               const std::function<void(int written, int arrays)>& written) {
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
  out << "    <Piece NumberOfPoints=\"" << grid.points << "\" NumberOfCells=\"" << grid.cells
      << "\">\n";
  const int arrays = static_cast<int>(grid.point_data.size() + grid.cell_data.size()) + 4;
  int count = 0;
  const auto done = [&] {
    ++count;
    if (written) written(count, arrays);
  };
  // One room for the compressed blocks of every array, as large as the largest needs:
  // the pages one array made resident serve the next (each array's own room cost fresh
  // pages, about 10 us a page on this VM: 90,000 of them at 1e7).
  Room held;
  if (encoding == VtkEncoding::Zlib) held.reserve(largest_room(grid));
  write_data(out, "PointData", grid.point_data, encoding, held, done);
  write_data(out, "CellData", grid.cell_data, encoding, held, done);
  write_data(out, "Points", {grid.coordinates}, encoding, held, done);
  write_data(out, "Cells", {grid.connectivity, grid.offsets, grid.types}, encoding, held, done);
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
