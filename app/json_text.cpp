#include "app/json_text.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>

#include <nlohmann/json.hpp>

#include "solver/threads.hpp"

namespace fetic::app {

void JsonText::raw(std::string_view text) {
  buffer_.append(text);
  maybe_flush();
}

namespace {

// nlohmann's own shortest round-trip formatting (the one dump() calls), so that the bytes
// are those of dump(); null for NaN and infinities, as dump() writes them. `text` holds
// 64 characters (nlohmann's serializer's buffer); returns the length written.
std::size_t format_number(double value, char* text) {
  if (!std::isfinite(value)) {
    std::memcpy(text, "null", 4);
    return 4;
  }
  return static_cast<std::size_t>(nlohmann::detail::to_chars(text, text + 64, value) - text);
}

// Texts of recently formatted numbers, by their bits (direct-mapped).
struct FormattedNumbers {
  static constexpr int kBits = 10;
  struct Entry {
    std::uint64_t bits = 0;
    std::size_t length = 0;  // 0: empty
    char text[24];
  };
  std::array<Entry, std::size_t{1} << kBits> entries;
};

}  // namespace

void JsonText::number(double value) {
  char text[64];
  buffer_.append(text, format_number(value, text));
  maybe_flush();
}

void JsonText::recurring_number(double value) {
  thread_local FormattedNumbers cache;
  const auto bits = std::bit_cast<std::uint64_t>(value);
  auto& entry = cache.entries[(bits * 0x9E3779B97F4A7C15ull) >> (64 - FormattedNumbers::kBits)];
  if (entry.length == 0 || entry.bits != bits) {
    char text[64];
    const std::size_t length = format_number(value, text);
    if (length <= sizeof entry.text) {
      entry.bits = bits;
      entry.length = length;
      std::memcpy(entry.text, text, length);
    }
    buffer_.append(text, length);
  } else {
    buffer_.append(entry.text, entry.length);
  }
  maybe_flush();
}

void JsonText::number(long long value) {
  char text[24];
  const auto result = std::to_chars(text, text + sizeof text, value);
  buffer_.append(text, static_cast<std::size_t>(result.ptr - text));
  maybe_flush();
}

void JsonText::string(std::string_view text) {
  raw(nlohmann::ordered_json(std::string(text)).dump());
}

namespace {

// A separator, a line break and the indentation that follow every item of an array: one
// copy from here instead of a character, a fill and a comma apiece (the result file of a
// 1e7-unknown solve has 73 million such lines).
constexpr std::string_view kLineStart =
    ",\n                                                                ";
constexpr int kMostIndent = static_cast<int>(kLineStart.size()) - 2;

}  // namespace

void JsonText::newline(int depth) {
  if (depth <= kMostIndent) {
    buffer_.append(kLineStart.substr(1, static_cast<std::size_t>(depth) + 1));
    return;
  }
  buffer_.push_back('\n');
  buffer_.append(static_cast<std::size_t>(depth), ' ');
}

void JsonText::next_item(bool comma, int depth) {
  if (comma && depth <= kMostIndent) {
    buffer_.append(kLineStart.substr(0, static_cast<std::size_t>(depth) + 2));
    return;
  }
  if (comma) buffer_.push_back(',');
  newline(depth);
}

void JsonText::member(std::string_view key, int depth, bool first) {
  next_item(!first, depth);
  string(key);
  raw(": ");
}

void JsonText::parallel_items(std::size_t count, int depth, ItemWriter item, void* context) {
  raw("[");
  runs_.resize(kRunsAtOnce);
  for (std::size_t first = 0; first < count; first += kRun * kRunsAtOnce) {
    const std::size_t last = std::min(count, first + kRun * kRunsAtOnce);
    const std::size_t used = (last - first + kRun - 1) / kRun;
    // About a microsecond per item (threads.hpp's unit).
    const int threads = solver::threads_for(static_cast<long long>(last - first));
#pragma omp parallel for num_threads(threads) schedule(dynamic)
    for (std::size_t r = 0; r < used; ++r) {
      JsonText text(std::move(runs_[r]));
      const std::size_t end = std::min(last, first + (r + 1) * kRun);
      for (std::size_t k = first + r * kRun; k < end; ++k) {
        text.next_item(k > 0, depth + 1);
        item(context, text, k, depth + 1);
      }
      runs_[r] = text.take();
    }
    // Straight to the stream, not copied once more through buffer_.
    flush();
    for (std::size_t r = 0; r < used; ++r)
      if (out_)
        out_->write(runs_[r].data(), static_cast<std::streamsize>(runs_[r].size()));
      else
        buffer_.append(runs_[r]);
  }
  newline(depth);
  raw("]");
}

void JsonText::flush() {
  if (!out_ || buffer_.empty()) return;
  out_->write(buffer_.data(), static_cast<std::streamsize>(buffer_.size()));
  buffer_.clear();
}

}  // namespace fetic::app
