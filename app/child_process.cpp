#include "app/child_process.hpp"

#include <sys/wait.h>

#include <cerrno>
#include <csignal>
#include <thread>

namespace fetic::app {

void stop_child(pid_t child, std::chrono::milliseconds grace) {
  if (child <= 0) return;
  ::kill(child, SIGTERM);
  const auto deadline = std::chrono::steady_clock::now() + grace;
  int status = 0;
  for (;;) {
    const pid_t ended = ::waitpid(child, &status, WNOHANG);
    if (ended == child || (ended < 0 && errno != EINTR)) return;
    if (std::chrono::steady_clock::now() >= deadline) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  ::kill(child, SIGKILL);
  while (::waitpid(child, &status, 0) < 0 && errno == EINTR) {
  }
}

}  // namespace fetic::app
