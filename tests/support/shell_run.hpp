#pragma once
// Runs a shell command line (fetic with its arguments, or under mpirun) and captures its
// exit status and everything it printed, for the command-line tests. Header only: those
// tests do not link the program's libraries.

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

namespace fetic::test {

struct ShellRun {
  int status = -1;     // the exit status; -1 when killed by a signal
  std::string output;  // stdout and stderr interleaved
};

// A path in the temporary folder, unique per test process (ctest runs cases in parallel).
inline std::string temporary_path(const std::string& name) {
  return (std::filesystem::temp_directory_path() / (std::to_string(::getpid()) + "_" + name))
      .string();
}

// The path of a bundled scene, scenes/NAME (the tests' CMake sets the folder).
#ifdef FETIC_BUNDLED_SCENES_DIR
inline std::string scene(const std::string& name) {
  return std::string(FETIC_BUNDLED_SCENES_DIR) + "/" + name;
}
#endif

inline ShellRun run_shell(const std::string& command) {
  const std::string log = temporary_path("shell_run_output.txt");
  const int raw = std::system((command + " > " + log + " 2>&1").c_str());
  ShellRun result;
  result.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  std::ifstream in(log);
  result.output.assign(std::istreambuf_iterator<char>(in), {});
  std::filesystem::remove(log);
  return result;
}

// `fetic ARGUMENTS` through the shell (the tests' CMake sets the executable).
#ifdef FETIC_EXECUTABLE
inline ShellRun run(const std::string& arguments) {
  return run_shell(std::string(FETIC_EXECUTABLE) + " " + arguments);
}
#endif

}  // namespace fetic::test
