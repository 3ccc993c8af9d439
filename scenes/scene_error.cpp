#include "scenes/scene_error.hpp"

namespace fetic::scenes {

// Messages quote the file (toml++'s "saw 'x'", names given in the scene): a newline or
// another control character there would start a line that does not name the file (found
// by fuzz/fuzz_scene), so they are shown escaped.
std::string printable(const std::string& message) {
  std::string text;
  for (std::size_t i = 0; i < message.size(); ++i) {
    const char c = message[i];
    const auto byte = static_cast<unsigned char>(c);
    if (message.compare(i, 3, "\xEF\xBB\xBF") == 0) {  // a byte order mark, invisible
      text += "\\uFEFF";
      i += 2;
    } else if (c == '\n') {
      text += "\\n";
    } else if (c == '\r') {
      text += "\\r";
    } else if ((byte < 0x20 && c != '\t') || byte == 0x7f) {
      static const char digits[] = "0123456789abcdef";
      text += "\\x";
      text += digits[byte >> 4];
      text += digits[byte & 15];
    } else {
      text += c;
    }
  }
  return text;
}

std::string format_problems(const std::string& path, const std::vector<Problem>& problems) {
  std::string text;
  for (const Problem& problem : problems) {
    if (!text.empty()) text += '\n';
    text += printable(path);
    if (problem.line > 0) text += ':' + std::to_string(problem.line);
    text += ": " + printable(problem.message);
  }
  return text;
}

SceneError::SceneError(std::string path, std::vector<Problem> problems)
    : std::runtime_error(format_problems(path, problems)),
      path_(std::move(path)),
      problems_(std::move(problems)) {}

}  // namespace fetic::scenes
