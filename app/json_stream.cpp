#include "app/json_stream.hpp"

#include <cstdio>
#include <string_view>

#include "app/json_layout.hpp"

namespace fetic::app {
namespace {

using Json = nlohmann::ordered_json;

// A placeholder is a string no result holds: a control character and two numbers.
constexpr std::string_view kMark =
    "\x01"
    "deferred ";

bool is_placeholder(const Json& value) {
  return value.is_string() && value.get_ref<const std::string&>().rfind(kMark, 0) == 0;
}

bool holds_placeholder(const Json& value) {
  if (is_placeholder(value)) return true;
  if (!value.is_structured()) return false;
  for (const Json& item : value)
    if (holds_placeholder(item)) return true;
  return false;
}

void indent(std::ostream& out, int depth) {
  for (int k = 0; k < depth; ++k)
    out.put(' ');
}

// `text` (a dump(1) from depth 0) written at `depth`: every line after the first indented.
void write_indented(std::ostream& out, const std::string& text, int depth) {
  size_t from = 0;
  for (size_t at = text.find('\n'); at != std::string::npos; at = text.find('\n', from)) {
    out.write(text.data() + from, static_cast<std::streamsize>(at + 1 - from));
    indent(out, depth);
    from = at + 1;
  }
  out.write(text.data() + from, static_cast<std::streamsize>(text.size() - from));
}

class Writer {
 public:
  Writer(std::ostream& out, const std::vector<ElementMaker>& makers) : out_(out), makers_(makers) {}

  void value(const Json& v, int depth) {
    if (is_placeholder(v)) {
      int maker = 0, index = 0;
      std::sscanf(v.get_ref<const std::string&>().c_str() + kMark.size(), "%d %d", &maker, &index);
      value(makers_.at(static_cast<size_t>(maker))(index), depth);
      return;
    }
    if (!holds_placeholder(v)) {
      write_indented(out_, scalars_first(v).dump(1), depth);
      return;
    }
    if (v.is_array()) {
      out_ << "[\n";
      bool first = true;
      for (const Json& item : v) {
        if (!first) out_ << ",\n";
        first = false;
        indent(out_, depth + 1);
        value(item, depth + 1);
      }
      out_ << "\n";
      indent(out_, depth);
      out_ << "]";
      return;
    }
    // An object: its plain values first, then the structured ones (json_layout.hpp).
    out_ << "{\n";
    bool first = true;
    for (const bool structured : {false, true})
      for (const auto& [key, item] : v.items()) {
        if (item.is_structured() != structured) continue;
        if (!first) out_ << ",\n";
        first = false;
        indent(out_, depth + 1);
        out_ << Json(key).dump() << ": ";
        value(item, depth + 1);
      }
    out_ << "\n";
    indent(out_, depth);
    out_ << "}";
  }

 private:
  std::ostream& out_;
  const std::vector<ElementMaker>& makers_;
};

}  // namespace

Json deferred(int maker, int index) {
  return std::string(kMark) + std::to_string(maker) + " " + std::to_string(index);
}

void write_streamed(std::ostream& out, const Json& document,
                    const std::vector<ElementMaker>& makers) {
  Writer(out, makers).value(document, 0);
}

}  // namespace fetic::app
