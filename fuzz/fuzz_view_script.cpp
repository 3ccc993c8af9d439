// libFuzzer target: arbitrary bytes as a saved view (app/view_file.hpp, through the JSON
// reader of app/json_input.hpp) and as a window script (app/gui/script.hpp). Invariants
// (any violation aborts, i.e. is a crash):
//   - a view is read or refused with ViewFileError, whose message starts with the file's
//     name, is one line of bounded length and carries no raw control character; no other
//     exception escapes (a number beyond the double range used to abort the program);
//   - a view that is read is written again by view_json() and reads back the same;
//   - a script parses into actions and errors without throwing; every error names a line
//     of the text and is short and printable; every action's line exists.
// Build and run: scripts/fuzz.sh [SECONDS] (the scene loader's and this target share it).

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>
#include <string_view>
#include <vector>

#include "app/gui/script.hpp"
#include "app/view_file.hpp"

namespace {

const std::string kPath = "fuzz-view.json";

[[noreturn]] void violated(const char* what, const std::string& detail) {
  std::fprintf(stderr, "fuzz_view_script: invariant violated: %s\n%.2000s\n", what, detail.c_str());
  std::abort();
}

void check_message(const std::string& message, std::size_t limit) {
  if (message.size() > limit) violated("a message longer than its limit", message);
  for (const char c : message)
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f)
      violated("a raw control character in a message", message);
}

void check_view(const std::string& text) {
  try {
    const fetic::app::SavedView view = fetic::app::parse_view(text, kPath);
    const std::string written = fetic::app::view_json(view);
    const fetic::app::SavedView back = fetic::app::parse_view(written, kPath);
    if (fetic::app::view_json(back) != written)
      violated("a view read back differs from the one written", written);
  } catch (const fetic::app::ViewFileError& error) {
    const std::string message = error.what();
    if (message.compare(0, kPath.size() + 1, kPath + ":") != 0)
      violated("a view file message does not start with the file name", message);
    check_message(message, 600);
  } catch (const std::exception& error) {
    violated("an exception other than ViewFileError escaped", error.what());
  } catch (...) {
    violated("a non-standard exception escaped the view reader", "");
  }
}

void check_script(const std::string& text) {
  std::size_t lines = 1;
  for (const char c : text)
    lines += c == '\n';
  try {
    std::vector<fetic::app::gui::ScriptError> errors;
    const auto actions = fetic::app::gui::parse_script(text, errors);
    for (const auto& error : errors) {
      if (error.line < 1 || static_cast<std::size_t>(error.line) > lines)
        violated("a script error names a line the text does not have", error.message);
      check_message(error.message, 400);
    }
    for (const auto& action : actions)
      if (action.line < 1 || static_cast<std::size_t>(action.line) > lines ||
          action.request.script_line != action.line)
        violated("a script action names a line the text does not have", text);
  } catch (const std::exception& error) {
    violated("an exception escaped the script parser", error.what());
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  check_view(text);
  check_script(text);
  return 0;
}
