#include "app/json_stream.hpp"

#include <cstdio>
#include <string_view>
#include <utility>

#include "app/json_layout.hpp"

namespace fetic::app {
namespace {

using Json = nlohmann::ordered_json;

// A placeholder is a string no result holds: a control character and two numbers.
constexpr std::string_view kMark =
    "\x01"
    "deferred ";
constexpr std::string_view kWrittenMark =
    "\x01"
    "written ";

bool starts_with(const Json& value, std::string_view mark) {
  return value.is_string() && value.get_ref<const std::string&>().rfind(mark, 0) == 0;
}

bool is_placeholder(const Json& value) {
  return starts_with(value, kMark) || starts_with(value, kWrittenMark);
}

// The two numbers after a placeholder's mark.
std::pair<int, int> placeholder_numbers(const Json& value, std::string_view mark) {
  int first = 0, second = 0;
  std::sscanf(value.get_ref<const std::string&>().c_str() + mark.size(), "%d %d", &first, &second);
  return {first, second};
}

bool holds_placeholder(const Json& value) {
  if (is_placeholder(value)) return true;
  if (!value.is_structured()) return false;
  for (const Json& item : value)
    if (holds_placeholder(item)) return true;
  return false;
}

// `text` (a dump(1) from depth 0) written at `depth`: every line after the first indented.
void write_indented(JsonText& out, const std::string& text, int depth) {
  size_t from = 0;
  for (size_t at = text.find('\n'); at != std::string::npos; at = text.find('\n', from)) {
    out.raw(std::string_view(text).substr(from, at - from));
    out.newline(depth);
    from = at + 1;
  }
  out.raw(std::string_view(text).substr(from));
}

class Writer {
 public:
  Writer(JsonText& out, const std::vector<ElementMaker>& makers,
         const std::vector<ElementWriter>& writers)
      : out_(out), makers_(makers), writers_(writers) {}

  void value(const Json& v, int depth) {
    if (starts_with(v, kMark)) {
      const auto [maker, index] = placeholder_numbers(v, kMark);
      value(makers_.at(static_cast<size_t>(maker))(index), depth);
      return;
    }
    if (starts_with(v, kWrittenMark)) {
      const auto [writer, index] = placeholder_numbers(v, kWrittenMark);
      writers_.at(static_cast<size_t>(writer))(out_, index, depth);
      return;
    }
    if (!holds_placeholder(v)) {
      write_indented(out_, scalars_first(v).dump(1), depth);
      return;
    }
    if (v.is_array()) {
      out_.array(v.size(), depth, [&](size_t k, int inner) { value(v[k], inner); });
      return;
    }
    // An object: its plain values first, then the structured ones (json_layout.hpp).
    out_.raw("{");
    bool first = true;
    for (const bool structured : {false, true})
      for (const auto& [key, item] : v.items()) {
        if (item.is_structured() != structured) continue;
        out_.member(key, depth + 1, first);
        first = false;
        value(item, depth + 1);
      }
    out_.newline(depth);
    out_.raw("}");
  }

 private:
  JsonText& out_;
  const std::vector<ElementMaker>& makers_;
  const std::vector<ElementWriter>& writers_;
};

}  // namespace

Json deferred(int maker, int index) {
  return std::string(kMark) + std::to_string(maker) + " " + std::to_string(index);
}

Json written(int writer, int index) {
  return std::string(kWrittenMark) + std::to_string(writer) + " " + std::to_string(index);
}

void write_streamed(std::ostream& out, const Json& document, const StreamedParts& parts) {
  JsonText text(out);
  Writer(text, parts.makers, parts.writers).value(document, 0);
}

void write_streamed(std::ostream& out, const Json& document,
                    const std::vector<ElementMaker>& makers) {
  write_streamed(out, document, StreamedParts{makers, {}});
}

}  // namespace fetic::app
