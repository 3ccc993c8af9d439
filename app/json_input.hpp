#pragma once
// Reading the small input files of the window and the renderer - view files (JSON) and
// window scripts - with one policy: a size limit for every kind of file (a FIFO or
// /dev/stdin is read up to it), folders and devices refused, a signal while waiting on a
// FIFO ends the reading (the command then exits 130), and for JSON one parser that
// refuses a number beyond the range of a double naming the file, the line, the entry and
// the entry's range instead of letting the parser's exception escape.

#include <cstddef>
#include <functional>
#include <stdexcept>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

namespace fetic::app {

// Largest view file or window script read. A view is a few hundred bytes (with one
// lateral scale per strut, a few kB); a script a line per action.
inline constexpr std::size_t kMaxInputFileBytes = std::size_t{8} << 20;

// An input that cannot be read or parsed; the message names the file.
class InputFileError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The whole file (`what`: "view file", "script", for messages). Regular files and FIFOs
// (also /dev/stdin as a pipe) up to kMaxInputFileBytes; a folder or a device is refused.
// A SIGINT/SIGTERM while waiting ends it with InputFileError (app/interrupt.hpp's
// interrupted() is then true).
std::string read_input_file(const std::string& path, const std::string& what);

// Parses JSON text read from `path`. Syntax errors name the line; a number beyond the
// double range names its entry ("zoom", "center[0]", "scales.force") and, when
// `range_of(entry)` returns one, the entry's range. Nesting deeper than 16 is refused.
nlohmann::json parse_json_input(const std::string& text, const std::string& path,
                                const std::string& what,
                                const std::function<std::string(const std::string&)>& range_of);

// A value quoted in a message: control characters escaped (\x00, \n), at most `limit`
// characters, longer ones cut with an ellipsis that says how long the value was.
std::string quoted_value(std::string_view value, std::size_t limit = 80);

}  // namespace fetic::app
