#pragma once
// A fetic child started with fork and exec, its standard output and error both into one
// log file, for the tests that signal it at a chosen moment (solve_interrupt_test,
// render_interrupt_test) and read what it printed in order.

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <string>
#include <thread>
#include <vector>

namespace fetic::test {

inline std::string read_bytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

// Runs `fetic ARGS...` with stdout and stderr into `log`; returns the child's pid.
inline pid_t start_fetic(const std::vector<std::string>& args, const std::filesystem::path& log) {
  const pid_t child = ::fork();
  if (child == 0) {
    std::FILE* file = std::fopen(log.c_str(), "w");
    if (file) {
      ::dup2(::fileno(file), 1);
      ::dup2(::fileno(file), 2);
    }
    std::vector<char*> argv{const_cast<char*>("fetic")};
    for (const std::string& arg : args)
      argv.push_back(const_cast<char*>(arg.c_str()));
    argv.push_back(nullptr);
    ::execv(FETIC_EXECUTABLE, argv.data());
    ::_exit(127);
  }
  return child;
}

// Waits for the child with a bound; on timeout kills it and returns nullopt.
inline std::optional<int> wait_bounded(pid_t child, std::chrono::seconds limit) {
  const auto deadline = std::chrono::steady_clock::now() + limit;
  int status = 0;
  while (std::chrono::steady_clock::now() < deadline) {
    if (::waitpid(child, &status, WNOHANG) == child) return status;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  ::kill(child, SIGKILL);
  ::waitpid(child, &status, 0);
  return std::nullopt;
}

// Polls `reached` every `poll` until it holds (true), or the child has ended or `limit`
// has passed (false). The child is left as it is: running, or ended and not collected.
template <class Condition>
bool wait_for(pid_t child, Condition reached, std::chrono::seconds limit,
              std::chrono::milliseconds poll) {
  const auto deadline = std::chrono::steady_clock::now() + limit;
  while (!reached()) {
    siginfo_t info{};
    if (::waitid(P_PID, static_cast<id_t>(child), &info, WEXITED | WNOHANG | WNOWAIT) == 0 &&
        info.si_pid == child)
      return false;
    if (std::chrono::steady_clock::now() >= deadline) return false;
    std::this_thread::sleep_for(poll);
  }
  return true;
}

// Kills the child and collects it.
inline void kill_child(pid_t child) {
  ::kill(child, SIGKILL);
  ::waitpid(child, nullptr, 0);
}

}  // namespace fetic::test
