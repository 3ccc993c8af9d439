#include "scenes/scene_text.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <vector>

namespace fetic::scenes {
namespace {

std::string mebibytes(double bytes) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f MiB", bytes / (1 << 20));
  return text;
}

SceneError read_error(const std::string& path, const std::string& message) {
  return SceneError(path, {{0, message}});
}

// Repeats a call interrupted by a signal, unless `stop` says the run ends.
template <class Call>
auto retrying(Call call, const std::function<bool()>& stop, const std::string& path,
              const char* waiting) {
  while (true) {
    const auto result = call();
    if (result >= 0 || errno != EINTR) return result;
    if (stop && stop())
      throw read_error(path, std::string("interrupted by a signal while ") + waiting);
  }
}

}  // namespace

std::string read_text_file(const std::string& path, std::size_t max_bytes, const std::string& what,
                           const std::function<bool()>& stop) {
  const std::string limit_text = "the limit for a " + what + " is " +
                                 mebibytes(static_cast<double>(max_bytes)) + " (" +
                                 std::to_string(max_bytes) + " bytes)";
  const int fd = retrying([&] { return ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NOCTTY); },
                          stop, path, ("opening the " + what + " (a FIFO without a writer?)").c_str());
  if (fd < 0) throw read_error(path, "cannot open the " + what + " (" + std::strerror(errno) + ")");
  struct Closer {
    int fd;
    ~Closer() { ::close(fd); }
  } closer{fd};
  struct stat info {};
  if (::fstat(fd, &info) != 0)
    throw read_error(path, "cannot read the " + what + " (" + std::strerror(errno) + ")");
  if (S_ISDIR(info.st_mode)) throw read_error(path, "is a directory, not a " + what);
  const bool regular = S_ISREG(info.st_mode);
  if (regular && static_cast<unsigned long long>(info.st_size) > max_bytes)
    throw read_error(path, "the file has " + mebibytes(static_cast<double>(info.st_size)) + " (" +
                               std::to_string(info.st_size) + " bytes); " + limit_text);
  // A regular file is read to its size (plus one byte, to see it growing); any other
  // stream in blocks, up to one byte beyond the limit.
  std::string text;
  text.resize(regular ? static_cast<size_t>(info.st_size) + 1 : size_t{1} << 16);
  size_t used = 0;
  while (true) {
    if (used == text.size()) {
      if (used > max_bytes) break;
      text.resize(std::min(text.size() * 2, max_bytes + 1));
    }
    const ssize_t n = retrying([&] { return ::read(fd, text.data() + used, text.size() - used); },
                               stop, path, ("reading the " + what).c_str());
    if (n < 0) throw read_error(path, "cannot read the " + what + " (" + std::strerror(errno) + ")");
    if (n == 0) break;
    used += static_cast<size_t>(n);
  }
  if (used > max_bytes)
    throw read_error(path, std::string(regular ? "the file grew while it was read and has "
                                               : "the stream gave ") +
                               "more than " + std::to_string(max_bytes) + " bytes; " + limit_text);
  text.resize(used);
  return text;
}

std::string read_scene_text(const std::string& path, const std::function<bool()>& stop) {
  return read_text_file(path, kMaxSceneFileBytes, "scene file", stop);
}

Problem nesting_problem(std::string_view text) {
  // Levels: the root table is 0. A header segment counts 2 (an array of tables adds a
  // table inside an array at each of its segments), a key segment 1, an array or inline
  // table 1. Over-counting is harmless: a scene nests 4 deep.
  enum class Mode { LineStart, Header, Key, Value };
  struct Container {
    char kind;
    int outer;  // the depth of the value that holds it
  };
  Mode mode = Mode::LineStart;
  std::vector<Container> containers;
  int line = 1;
  int header_depth = 0;
  int key_depth = 0, value_depth = 0;
  bool segment_open = false;
  int deepest_line = 0;
  const auto check = [&](int depth) {
    if (depth > kMaxNesting && deepest_line == 0) deepest_line = line;
  };
  const auto start_key = [&](int base) {
    mode = Mode::Key;
    key_depth = base;
    segment_open = false;
  };
  // A key or header segment starts at a bare character or a quoted key.
  const auto segment = [&] {
    if (segment_open) return;
    segment_open = true;
    if (mode == Mode::Header) {
      header_depth += 2;
      check(header_depth);
    } else {
      ++key_depth;
      check(key_depth);
    }
  };
  const size_t size = text.size();
  for (size_t i = 0; i < size && deepest_line == 0; ++i) {
    const char c = text[i];
    if (c == '\n') {
      ++line;
      if (containers.empty()) mode = Mode::LineStart;
      continue;
    }
    if (c == ' ' || c == '\t' || c == '\r') continue;
    if (c == '#') {
      while (i + 1 < size && text[i + 1] != '\n')
        ++i;
      continue;
    }
    if (c == '"' || c == '\'') {  // a string: a key segment, or a value to skip
      const bool triple = i + 2 < size && text[i + 1] == c && text[i + 2] == c;
      if (mode == Mode::LineStart) start_key(header_depth);
      if (mode != Mode::Value) segment();
      i += triple ? 3 : 1;
      for (; i < size; ++i) {
        if (text[i] == '\n') {
          ++line;
          if (!triple) break;  // an unterminated one-line string: toml++ reports it
        }
        if (c == '"' && text[i] == '\\') {
          if (i + 1 < size && text[i + 1] == '\n') ++line;
          ++i;
          continue;
        }
        if (text[i] != c) continue;
        if (!triple) break;
        if (i + 2 < size && text[i + 1] == c && text[i + 2] == c) {
          i += 2;
          while (i + 1 < size && text[i + 1] == c)  // up to two quotes before the end
            ++i;
          break;
        }
      }
      continue;
    }
    switch (mode) {
      case Mode::LineStart:
        if (c == '[') {
          mode = Mode::Header;
          header_depth = 0;
          segment_open = false;
          if (i + 1 < size && text[i + 1] == '[') ++i;
          break;
        }
        start_key(header_depth);
        [[fallthrough]];
      case Mode::Key:
        if (c == '.') {
          segment_open = false;
        } else if (c == '=') {
          mode = Mode::Value;
          value_depth = key_depth;
        } else if (c == '}' && !containers.empty()) {  // an empty inline table
          value_depth = containers.back().outer;
          containers.pop_back();
          mode = Mode::Value;
        } else {
          segment();
        }
        break;
      case Mode::Header:
        if (c == '.') {
          segment_open = false;
        } else if (c == ']') {
          if (i + 1 < size && text[i + 1] == ']') ++i;
          mode = Mode::LineStart;
        } else {
          segment();
        }
        break;
      case Mode::Value:
        if (c == '[' || c == '{') {
          containers.push_back({c, value_depth});
          ++value_depth;  // the elements of an array, the keys of an inline table
          check(value_depth);
          if (c == '{') start_key(value_depth);
        } else if (c == ']' || c == '}') {
          if (!containers.empty()) {
            value_depth = containers.back().outer;
            containers.pop_back();
          }
        } else if (c == ',' && !containers.empty() && containers.back().kind == '{') {
          start_key(containers.back().outer + 1);
        }
        break;
    }
  }
  if (deepest_line == 0) return {0, ""};
  return {deepest_line, "the TOML nests deeper than " + std::to_string(kMaxNesting) +
                            " levels (table headers, dotted keys, arrays and inline tables "
                            "together; a scene needs 4)"};
}

}  // namespace fetic::scenes
