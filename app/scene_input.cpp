#include "app/scene_input.hpp"

#include <sys/stat.h>

#include <filesystem>
#include <iostream>
#include <new>
#include <stdexcept>

#include "app/data_paths.hpp"
#include "app/exit_codes.hpp"
#include "app/interrupt.hpp"
#include "app/out_of_memory.hpp"
#include "scenes/load_scene.hpp"

namespace fetic::app {

namespace {

std::string counts(const scenes::Scene& scene) {
  long long subdomains = 0;
  for (const scenes::Strut& strut : scene.struts)
    subdomains += static_cast<long long>(strut.subdomains) *
                  (scenes::nodes_across(scene, strut) > 1 ? strut.subdomains_across : 1);
  return std::to_string(scenes::unknowns(scene)) + " unknowns, " +
         std::to_string(scene.struts.size()) + " struts, " + std::to_string(subdomains) +
         " subdomains, " + std::to_string(scene.contacts.size()) + " contacts";
}

// "  looked in: ..." after a scene that could not be opened, when it was looked up by name.
void report_where_looked(const std::string& path) {
  std::error_code error;
  if (std::filesystem::exists(std::filesystem::symlink_status(path, error))) return;
  const SceneLookup lookup = find_scene(path);
  if (lookup.found || lookup.looked_in.empty()) return;
  std::cerr << "  looked in:";
  for (const std::string& place : lookup.looked_in)
    std::cerr << "\n    " << scenes::printable(place);
  if (lookup.looked_in.size() == 1)
    std::cerr << "\n  (no bundled scene folder found: set FETIC_DATA_DIR to the folder that "
                 "holds scenes/)";
  std::cerr << "\n  `fetic scenes` lists the bundled scenes\n";
}

}  // namespace

CLI::Option* look_up_bundled_scenes(CLI::Option* option) {
  // (the transform's result replaces the value)
  return option->transform([](std::string argument) { return resolve_scene(argument); }, "", "");
}

std::string memory_problem(const scenes::Scene& scene, const MemoryUse& use) {
  if (!memory_check_enabled()) return "";
  const auto available = available_memory();
  if (!available) return "";
  const MemoryEstimate need = estimate_memory(scene, use);
  if (need.bytes <= available->bytes) return "";
  return "not enough memory: " + need.largest + " on this scene (" + counts(scene) +
         ") needs about " + memory_text(need.bytes) + ", and " + memory_text(available->bytes) +
         " is available (" + available->limited_by + ")";
}

bool memory_suffices(const scenes::Scene& scene, const std::string& path, const MemoryUse& use,
                     int& status) {
  const std::string problem = memory_problem(scene, use);
  if (problem.empty()) return true;
  std::cerr << scenes::printable(path) << ": " << problem
            << "; refused before assembly (FETIC_MEMORY_CHECK=off tries anyway)\n";
  status = kExitOutOfMemory;
  return false;
}

std::optional<scenes::Scene> load_scene_or_report(const std::string& path, int& status) {
  Activity activity("reading the scene");
  struct stat info {};
  if (memory_check_enabled() && ::stat(path.c_str(), &info) == 0 && S_ISREG(info.st_mode)) {
    const double need = estimate_parse_memory(static_cast<double>(info.st_size));
    const auto available = available_memory();
    if (available && need > available->bytes) {
      std::cerr << scenes::printable(path) << ": not enough memory: reading this scene file ("
                << memory_text(static_cast<double>(info.st_size)) << ") needs about "
                << memory_text(need) << ", and " << memory_text(available->bytes)
                << " is available (" << available->limited_by
                << "); refused before reading (FETIC_MEMORY_CHECK=off tries anyway)\n";
      status = kExitOutOfMemory;
      return std::nullopt;
    }
  }
  try {
    scenes::Scene scene = scenes::load_scene_file(path, [] { return interrupted(); });
    for (const scenes::Problem& warning : scene.warnings)
      std::cerr << scenes::format_problems(path, {{warning.line, "warning: " + warning.message}})
                << '\n';
    return scene;
  } catch (const scenes::SceneError& error) {
    if (interrupted()) {
      std::cerr << scenes::printable(path) << ": interrupted by " << interrupt_name()
                << " while opening or reading the scene file\n";
      status = kExitInterrupted;
    } else {
      std::cerr << error.what() << '\n';
      report_where_looked(path);
      status = kExitInvalidScene;
    }
  } catch (const std::bad_alloc&) {
    std::cerr << scenes::printable(path) << ": out of memory while reading the scene\n";
    status = kExitOutOfMemory;
  } catch (const std::length_error&) {  // a string or vector beyond what can be allocated
    std::cerr << scenes::printable(path) << ": out of memory while reading the scene\n";
    status = kExitOutOfMemory;
  }
  return std::nullopt;
}

}  // namespace fetic::app
