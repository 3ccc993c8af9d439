#include "app/output_options.hpp"

namespace fetic::app {

CLI::Validator output_name(OutputKind kind) {
  const bool folder = kind == OutputKind::Folder;
  return CLI::Validator(
      [folder](std::string& text) -> std::string {
        if (!text.empty()) return "";
        return folder ? "an empty name writes nothing; give a folder name"
                      : "an empty name writes nothing; give a file name (- for standard output)";
      },
      "");
}

}  // namespace fetic::app
