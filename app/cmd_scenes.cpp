// fetic scenes: the bundled scenes, by the name that runs them, with their titles.

#include <iostream>
#include <string>

#include "app/commands.hpp"
#include "app/data_paths.hpp"
#include "app/exit_codes.hpp"
#include "scenes/load_scene.hpp"
#include "scenes/scene_error.hpp"

namespace fetic::app {
namespace {

// The scene's one-line title, or why it has none.
std::string title_of(const std::filesystem::path& file) {
  try {
    const scenes::Scene scene = scenes::load_scene_file(file.string());
    return scene.title.empty() ? "(no title)" : scenes::printable(scene.title);
  } catch (const scenes::SceneError&) {
    return "(not a valid scene)";
  }
}

int run_scenes() {
  const std::filesystem::path directory = data_directory();
  const auto files = bundled_scenes();
  if (files.empty()) {
    std::cerr << "fetic scenes: no bundled scene folder found (looked for share/fetic/scenes "
                 "beside the executable and in the source tree; FETIC_DATA_DIR sets it)\n";
    return kExitInvalidScene;
  }
  std::cout << "Bundled scenes in " << scenes::printable((directory / "scenes").string())
            << "\n(run one by name from any directory, e.g. fetic solve "
            << files.front().stem().string() << "):\n";
  for (const std::filesystem::path& file : files) {
    std::string name = file.stem().string();
    name.resize(std::max<size_t>(name.size(), 24), ' ');
    std::cout << "  " << name << ' ' << title_of(file) << '\n';
  }
  return kExitOk;
}

}  // namespace

void register_scenes(CLI::App& app, int& exit_code) {
  CLI::App* command = app.add_subcommand(
      "scenes", "List the bundled scenes with their titles (usable by name: fetic solve thesis)");
  command->callback([&exit_code] { exit_code = run_scenes(); });
}

}  // namespace fetic::app
