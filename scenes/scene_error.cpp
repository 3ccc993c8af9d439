#include "scenes/scene_error.hpp"

namespace fetic::scenes {

std::string format_problems(const std::string& path, const std::vector<Problem>& problems) {
  std::string text;
  for (const Problem& problem : problems) {
    if (!text.empty()) text += '\n';
    text += path;
    if (problem.line > 0) text += ':' + std::to_string(problem.line);
    text += ": " + problem.message;
  }
  return text;
}

SceneError::SceneError(std::string path, std::vector<Problem> problems)
    : std::runtime_error(format_problems(path, problems)),
      path_(std::move(path)),
      problems_(std::move(problems)) {}

}  // namespace fetic::scenes
