#pragma once
// JSON text written directly, byte for byte as nlohmann's dump(1) writes the same values:
// numbers by nlohmann's own formatting (shortest round trip, ".0" on whole doubles, null
// for NaN and infinities), one space of indentation per level, empty arrays as []. A
// strut of a 1e7-unknown result has ~1.4 million numbers; building them as JSON values,
// reordering and dumping them took most of the writing time (docs/BENCHMARKS.md,
// "Writing the outputs").

#include <cstddef>
#include <ostream>
#include <string>
#include <string_view>

namespace fetic::app {

class JsonText {
 public:
  explicit JsonText(std::ostream& out) : out_(out) { buffer_.reserve(kFlushAt + 256); }
  ~JsonText() { flush(); }
  JsonText(const JsonText&) = delete;
  JsonText& operator=(const JsonText&) = delete;

  void raw(std::string_view text);
  void number(double value);
  void number(long long value);
  void number(int value) { number(static_cast<long long>(value)); }
  void string(std::string_view text);  // quoted and escaped as nlohmann does
  void newline(int depth);             // a line break and `depth` spaces

  // `[`, then item(k, depth + 1) for k < count on lines of their own, then `]`: as dump(1).
  template <class Item>
  void array(std::size_t count, int depth, Item&& item) {
    if (count == 0) {
      raw("[]");
      return;
    }
    raw("[");
    for (std::size_t k = 0; k < count; ++k) {
      if (k > 0) raw(",");
      newline(depth + 1);
      item(k, depth + 1);
    }
    newline(depth);
    raw("]");
  }

  // One member of an object at `depth`: the separator, the indented key and ": ".
  void member(std::string_view key, int depth, bool first);

  void flush();

 private:
  static constexpr std::size_t kFlushAt = std::size_t{1} << 20;
  void maybe_flush() {
    if (buffer_.size() >= kFlushAt) flush();
  }
  std::ostream& out_;
  std::string buffer_;
};

}  // namespace fetic::app
