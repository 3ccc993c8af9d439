#include "app/data_paths.hpp"

#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <iterator>
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

SceneLookup find_scene(const std::string& argument) {
  SceneLookup lookup{argument, {}, false};
  std::error_code error;
  const fs::path given(argument);
  if (argument.empty() || fs::exists(fs::symlink_status(given, error)) || given.is_absolute()) {
    lookup.found = !argument.empty() && fs::exists(given, error);
    return lookup;
  }
  lookup.looked_in.push_back((fs::current_path(error) / given).lexically_normal().string());
  const fs::path directory = data_directory();
  if (directory.empty()) return lookup;
  // "scenes/thesis.toml" names the bundled folder's "thesis.toml"; "thesis" its ".toml".
  fs::path name = given.lexically_normal();
  if (name.empty() || *name.begin() == "..") return lookup;  // not a name in the folder
  if (auto part = name.begin();
      part != name.end() && *part == "scenes" && std::next(part) != name.end())
    name = name.lexically_relative("scenes");
  std::vector<fs::path> candidates{directory / "scenes" / name};
  if (name.extension() != ".toml")
    candidates.push_back(directory / "scenes" / (name.string() + ".toml"));
  for (const fs::path& candidate : candidates) {
    const fs::path normal = candidate.lexically_normal();
    lookup.looked_in.push_back(normal.string());
    if (fs::is_regular_file(normal, error)) {
      lookup.path = normal.string();
      lookup.found = true;
      return lookup;
    }
  }
  return lookup;
}

std::string resolve_scene(const std::string& argument) {
  return find_scene(argument).path;
}

std::vector<fs::path> bundled_scenes() {
  std::vector<fs::path> scenes;
  const fs::path directory = data_directory();
  std::error_code error;
  if (directory.empty()) return scenes;
  for (fs::directory_iterator entry(directory / "scenes", error), end; !error && entry != end;
       entry.increment(error))
    if (entry->path().extension() == ".toml" && entry->is_regular_file(error))
      scenes.push_back(entry->path());
  std::sort(scenes.begin(), scenes.end());
  return scenes;
}

std::string font_file(const std::string& name) {
  std::error_code error;
  const fs::path directory = data_directory();
  if (!directory.empty() && fs::exists(directory / "fonts" / name, error))
    return (directory / "fonts" / name).string();
  return "/usr/share/fonts/truetype/dejavu/" + name;
}

}  // namespace fetic::app
