#pragma once
// Every problem found in a scene file, each with the line where it is (0 when none).

#include <stdexcept>
#include <string>
#include <vector>

namespace fetic::scenes {

struct Problem {
  int line = 0;
  std::string message;
};

class SceneError : public std::runtime_error {
 public:
  SceneError(std::string path, std::vector<Problem> problems);
  const std::string& path() const { return path_; }
  const std::vector<Problem>& problems() const { return problems_; }

 private:
  std::string path_;
  std::vector<Problem> problems_;
};

// The text with control characters escaped (\n, \r, \xHH), so that a message quoting a
// file name or a value stays on one line.
std::string printable(const std::string& text);

// "path:line: message" (or "path: message" without a line), one problem per line.
std::string format_problems(const std::string& path, const std::vector<Problem>& problems);

}  // namespace fetic::scenes
