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
#include <type_traits>
#include <utility>
#include <vector>

namespace fetic::app {

class JsonText {
 public:
  explicit JsonText(std::ostream& out) : out_(&out) { buffer_.reserve(kFlushAt + 256); }
  // Text kept in memory, appended to `buffer` (take() hands it back): a piece that
  // another JsonText writes. The buffer keeps its capacity, so that reusing it costs no
  // new pages (a page fault costs more on this VM than formatting a number).
  explicit JsonText(std::string&& buffer) : buffer_(std::move(buffer)) { buffer_.clear(); }
  ~JsonText() { flush(); }
  JsonText(const JsonText&) = delete;
  JsonText& operator=(const JsonText&) = delete;

  void raw(std::string_view text);
  void number(double value);
  // The same text as number(), for values that recur (a mesh's node coordinates: a strut
  // drawn along an axis has a few hundred distinct ones among 200,000): the text of each
  // value is kept in a small cache per thread and copied when the value comes again.
  void recurring_number(double value);
  void number(long long value);
  void number(int value) { number(static_cast<long long>(value)); }
  void string(std::string_view text);  // quoted and escaped as nlohmann does
  void newline(int depth);             // a line break and `depth` spaces
  // What comes before an array's item: a comma unless it is the first, then newline(depth).
  void next_item(bool comma, int depth);

  // `[`, then item(k, depth + 1) for k < count on lines of their own, then `]`: as dump(1).
  template <class Item>
  void array(std::size_t count, int depth, Item&& item) {
    if (count == 0) {
      raw("[]");
      return;
    }
    raw("[");
    for (std::size_t k = 0; k < count; ++k) {
      next_item(k > 0, depth + 1);
      item(k, depth + 1);
    }
    newline(depth);
    raw("]");
  }

  // The same bytes as array(), for long arrays: item(text, k, depth + 1) writes item k
  // into `text`; runs of items are written on the process' threads, each into its own
  // text, and joined in order. Formatting numbers was half of writing the 1.6 GB result
  // file of a 1e7-unknown solve, on one core (docs/BENCHMARKS.md, "Outputs at 1e7").
  template <class Item>
  void parallel_array(std::size_t count, int depth, Item&& item) {
    if (count < kRun) {
      array(count, depth, [&](std::size_t k, int inner) { item(*this, k, inner); });
      return;
    }
    const auto call = [](void* context, JsonText& text, std::size_t k, int inner) {
      (*static_cast<std::remove_reference_t<Item>*>(context))(text, k, inner);
    };
    parallel_items(count, depth, call, const_cast<void*>(static_cast<const void*>(&item)));
  }

  // The text written so far, when kept in memory (the constructor from a string).
  std::string take() { return std::move(buffer_); }

  // One member of an object at `depth`: the separator, the indented key and ": ".
  void member(std::string_view key, int depth, bool first);

  void flush();

 private:
  static constexpr std::size_t kFlushAt = std::size_t{1} << 20;
  static constexpr std::size_t kRun = 4096;       // items a thread writes at a time
  static constexpr std::size_t kRunsAtOnce = 64;  // runs held before they are joined
  using ItemWriter = void (*)(void* context, JsonText& text, std::size_t k, int depth);
  // parallel_array's work (json_text.cpp: the header is also compiled without OpenMP).
  void parallel_items(std::size_t count, int depth, ItemWriter item, void* context);
  void maybe_flush() {
    if (out_ && buffer_.size() >= kFlushAt) flush();
  }
  std::ostream* out_ = nullptr;
  std::string buffer_;
  std::vector<std::string> runs_;  // parallel_array's pieces, kept for their capacity
};

}  // namespace fetic::app
