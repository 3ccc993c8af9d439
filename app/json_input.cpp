#include "app/json_input.hpp"

#include <sys/stat.h>

#include <cerrno>
#include <cstring>
#include <vector>

#include "app/interrupt.hpp"
#include "scenes/message_text.hpp"
#include "scenes/scene_error.hpp"
#include "scenes/scene_text.hpp"

namespace fetic::app {
namespace {

using nlohmann::json;

constexpr std::size_t kMaxJsonDepth = 16;  // a view nests 3 deep

// Builds the document with nlohmann's own DOM builder while keeping the path to the value
// being parsed, so that an error can name its entry.
class PathTrackingSax {
 public:
  PathTrackingSax(json& root, const std::string& path, const std::string& what,
                  const std::function<std::string(const std::string&)>& range_of)
      : dom_(root), path_(path), what_(what), range_of_(range_of) {}

  bool null() { return value(dom_.null()); }
  bool boolean(bool x) { return value(dom_.boolean(x)); }
  bool number_integer(json::number_integer_t x) { return value(dom_.number_integer(x)); }
  bool number_unsigned(json::number_unsigned_t x) { return value(dom_.number_unsigned(x)); }
  bool number_float(json::number_float_t x, const std::string& text) {
    return value(dom_.number_float(x, text));
  }
  bool string(std::string& x) { return value(dom_.string(x)); }
  bool binary(json::binary_t& x) { return value(dom_.binary(x)); }
  bool start_object(std::size_t n) { return open(false) && dom_.start_object(n); }
  bool key(std::string& k) {
    levels_.back().key = k;
    return dom_.key(k);
  }
  bool end_object() { return close() && dom_.end_object(); }
  bool start_array(std::size_t n) { return open(true) && dom_.start_array(n); }
  bool end_array() { return close() && dom_.end_array(); }

  bool parse_error(std::size_t byte, const std::string& token,
                   const nlohmann::detail::exception& error) {
    const std::string where = scenes::printable(path_) + ":" + std::to_string(line_at(byte));
    if (error.id == 406) {  // a number beyond the double range
      const std::string entry = current_entry();
      const std::string range = range_of_ ? range_of_(entry) : "";
      throw InputFileError(where + ": '" + quoted_value(entry) + "' is " + quoted_value(token) +
                           ", beyond the range of a number (about 1.8e308)" +
                           (range.empty() ? "" : "; it must be " + range));
    }
    throw InputFileError(where + ": not a JSON " + what_ + " (" + quoted_value(error.what(), 200) +
                         ")");
  }

  void set_text(const std::string& text) { text_ = &text; }

 private:
  struct Level {
    bool array = false;
    std::size_t index = 0;
    std::string key;
  };

  bool value(bool ok) {
    if (!levels_.empty() && levels_.back().array) ++levels_.back().index;
    return ok;
  }
  bool open(bool array) {
    if (levels_.size() >= kMaxJsonDepth)
      throw InputFileError(scenes::printable(path_) + ": the " + what_ + " nests deeper than " +
                           std::to_string(kMaxJsonDepth) + " levels");
    levels_.push_back({array, 0, {}});
    return true;
  }
  bool close() {
    levels_.pop_back();
    return value(true);
  }
  std::string current_entry() const {
    std::string entry;
    for (const Level& level : levels_) {
      if (level.array)
        entry += "[" + std::to_string(level.index) + "]";
      else
        entry += (entry.empty() ? "" : ".") + level.key;
    }
    return entry;
  }
  long line_at(std::size_t byte) const {
    if (!text_) return 1;
    long line = 1;
    for (std::size_t i = 0; i + 1 < byte && i < text_->size(); ++i)
      line += (*text_)[i] == '\n';
    return line;
  }

  nlohmann::detail::json_sax_dom_parser<json> dom_;
  const std::string& path_;
  const std::string& what_;
  const std::function<std::string(const std::string&)>& range_of_;
  const std::string* text_ = nullptr;
  std::vector<Level> levels_;
};

}  // namespace

std::string read_input_file(const std::string& path, const std::string& what) {
  const std::string name = scenes::printable(path);
  struct stat info {};
  if (::stat(path.c_str(), &info) == 0) {
    if (S_ISDIR(info.st_mode)) throw InputFileError(name + ": is a folder, not a " + what);
    // A terminal, /dev/zero or /dev/urandom: nothing a file was saved to.
    if (S_ISCHR(info.st_mode) || S_ISBLK(info.st_mode))
      throw InputFileError(name + ": is a device, not a " + what);
  }
  try {
    return scenes::read_text_file(path, kMaxInputFileBytes, what, [] { return interrupted(); });
  } catch (const scenes::SceneError& error) {
    throw InputFileError(error.what());
  }
}

json parse_json_input(const std::string& text, const std::string& path, const std::string& what,
                      const std::function<std::string(const std::string&)>& range_of) {
  json root;
  PathTrackingSax sax(root, path, what, range_of);
  sax.set_text(text);
  json::sax_parse(text, &sax);
  return root;
}

std::string quoted_value(std::string_view value, std::size_t limit) {
  return scenes::shortened(value, limit);
}

}  // namespace fetic::app
