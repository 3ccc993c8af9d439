#include "app/data_paths.hpp"

#include <unistd.h>

#include <cstdlib>
#include <system_error>

namespace fetic::app {
namespace {

namespace fs = std::filesystem;

bool is_data_directory(const fs::path& directory) {
  std::error_code error;
  return !directory.empty() && fs::is_directory(directory / "scenes", error);
}

fs::path executable_directory() {
  std::error_code error;
  const fs::path self = fs::read_symlink("/proc/self/exe", error);
  return error ? fs::path() : self.parent_path();
}

}  // namespace

fs::path data_directory() {
  if (const char* variable = std::getenv("FETIC_DATA_DIR"); variable && *variable)
    return fs::path(variable);
  const fs::path installed = executable_directory() / FETIC_INSTALLED_DATA_RELATIVE;
  if (is_data_directory(installed)) return installed.lexically_normal();
  const fs::path source(FETIC_SOURCE_DATA_DIR);
  if (is_data_directory(source)) return source;
  return {};
}

std::string bundled_scene(const std::string& name) {
  const fs::path directory = data_directory();
  return ((directory.empty() ? fs::path("scenes") : directory / "scenes") / name).string();
}

std::string font_file(const std::string& name) {
  std::error_code error;
  const fs::path directory = data_directory();
  if (!directory.empty() && fs::exists(directory / "fonts" / name, error))
    return (directory / "fonts" / name).string();
  return "/usr/share/fonts/truetype/dejavu/" + name;
}

}  // namespace fetic::app
