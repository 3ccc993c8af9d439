#include "app/scene_input.hpp"

#include <sys/stat.h>

#include <iostream>
#include <new>
#include <stdexcept>

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

}  // namespace

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
