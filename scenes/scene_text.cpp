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
  const int fd =
      retrying([&] { return ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NOCTTY); }, stop, path,
               ("opening the " + what + " (a FIFO without a writer?)").c_str());
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
    if (n < 0)
      throw read_error(path, "cannot read the " + what + " (" + std::strerror(errno) + ")");
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

namespace {

// Levels: the root table is 0. A header segment counts 2 (an array of tables adds a
// table inside an array at each of its segments), a key segment 1, an array or inline
// table 1. Over-counting is harmless: a scene nests 4 deep.
class NestingScanner {
 public:
  explicit NestingScanner(std::string_view text) : text_(text) {}

  // The line where the nesting first goes deeper than kMaxNesting, or 0.
  int run() {
    const size_t size = text_.size();
    for (size_t i = 0; i < size && deepest_line_ == 0; ++i) {
      const char c = text_[i];
      if (c == '\n') {
        ++line_;
        if (containers_.empty()) mode_ = Mode::LineStart;
      } else if (c == ' ' || c == '\t' || c == '\r') {
        continue;
      } else if (c == '#') {
        while (i + 1 < size && text_[i + 1] != '\n')
          ++i;
      } else if (c == '"' || c == '\'') {  // a string: a key segment, or a value to skip
        if (mode_ == Mode::LineStart) start_key(header_depth_);
        if (mode_ != Mode::Value) segment();
        skip_string(i, c);
      } else {
        structure(i, c);
      }
    }
    return deepest_line_;
  }

 private:
  enum class Mode { LineStart, Header, Key, Value };
  struct Container {
    char kind;
    int outer;  // the depth of the value that holds it
  };

  void check(int depth) {
    if (depth > kMaxNesting && deepest_line_ == 0) deepest_line_ = line_;
  }
  void start_key(int base) {
    mode_ = Mode::Key;
    key_depth_ = base;
    segment_open_ = false;
  }
  // A key or header segment starts at a bare character or a quoted key.
  void segment() {
    if (segment_open_) return;
    segment_open_ = true;
    if (mode_ == Mode::Header) {
      header_depth_ += 2;
      check(header_depth_);
    } else {
      ++key_depth_;
      check(key_depth_);
    }
  }
  // From the opening quote at i to the closing one.
  void skip_string(size_t& i, char quote) {
    const size_t size = text_.size();
    const bool triple = i + 2 < size && text_[i + 1] == quote && text_[i + 2] == quote;
    i += triple ? 3 : 1;
    for (; i < size; ++i) {
      if (text_[i] == '\n') {
        ++line_;
        if (!triple) break;  // an unterminated one-line string: toml++ reports it
      }
      if (quote == '"' && text_[i] == '\\') {
        if (i + 1 < size && text_[i + 1] == '\n') ++line_;
        ++i;
        continue;
      }
      if (text_[i] != quote) continue;
      if (!triple) break;
      if (i + 2 < size && text_[i + 1] == quote && text_[i + 2] == quote) {
        i += 2;
        while (i + 1 < size && text_[i + 1] == quote)  // up to two quotes before the end
          ++i;
        break;
      }
    }
  }
  // Anything else: headers, keys, values and their brackets.
  void structure(size_t& i, char c) {
    const bool doubled = i + 1 < text_.size() && text_[i + 1] == c;
    switch (mode_) {
      case Mode::LineStart:
        if (c == '[') {
          mode_ = Mode::Header;
          header_depth_ = 0;
          segment_open_ = false;
          if (doubled) ++i;
          break;
        }
        start_key(header_depth_);
        [[fallthrough]];
      case Mode::Key:
        if (c == '.') {
          segment_open_ = false;
        } else if (c == '=') {
          mode_ = Mode::Value;
          value_depth_ = key_depth_;
        } else if (c == '}' && !containers_.empty()) {  // an empty inline table
          value_depth_ = containers_.back().outer;
          containers_.pop_back();
          mode_ = Mode::Value;
        } else {
          segment();
        }
        break;
      case Mode::Header:
        if (c == '.') {
          segment_open_ = false;
        } else if (c == ']') {
          if (doubled) ++i;
          mode_ = Mode::LineStart;
        } else {
          segment();
        }
        break;
      case Mode::Value:
        value(c);
        break;
    }
  }
  void value(char c) {
    if (c == '[' || c == '{') {
      containers_.push_back({c, value_depth_});
      ++value_depth_;  // the elements of an array, the keys of an inline table
      check(value_depth_);
      if (c == '{') start_key(value_depth_);
    } else if (c == ']' || c == '}') {
      if (!containers_.empty()) {
        value_depth_ = containers_.back().outer;
        containers_.pop_back();
      }
    } else if (c == ',' && !containers_.empty() && containers_.back().kind == '{') {
      start_key(containers_.back().outer + 1);
    }
  }

  std::string_view text_;
  Mode mode_ = Mode::LineStart;
  std::vector<Container> containers_;
  int line_ = 1;
  int header_depth_ = 0;
  int key_depth_ = 0, value_depth_ = 0;
  bool segment_open_ = false;
  int deepest_line_ = 0;
};

}  // namespace

Problem nesting_problem(std::string_view text) {
  const int line = NestingScanner(text).run();
  if (line == 0) return {0, ""};
  return {line, "the TOML nests deeper than " + std::to_string(kMaxNesting) +
                    " levels (table headers, dotted keys, arrays and inline tables "
                    "together; a scene needs 4)"};
}

}  // namespace fetic::scenes
