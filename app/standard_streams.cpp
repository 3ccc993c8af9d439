#include "app/standard_streams.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <iostream>

#include "app/exit_codes.hpp"

namespace fetic::app {

void guard_standard_streams() {
  for (int fd = 0; fd <= 2; ++fd) {
    if (::fcntl(fd, F_GETFD) >= 0 || errno != EBADF) continue;
    // The root directory, read-only: exists everywhere, and writing to it fails.
    const int placeholder = ::open("/", O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (placeholder >= 0 && placeholder != fd) {
      ::dup2(placeholder, fd);
      ::close(placeholder);
    }
  }
  std::signal(SIGPIPE, SIG_IGN);
}

int finish_standard_output(int status) {
  errno = 0;
  std::cout.flush();
  const bool lost = !std::cout || std::fflush(stdout) != 0 || std::ferror(stdout);
  if (!lost) return status;
  const int error = errno;
  std::cerr << "fetic: standard output: cannot write ("
            << (error ? std::strerror(error) : "write error")
            << "); the printed report is incomplete\n";
  return status == kExitOk || status == kExitNotConverged ? kExitOutput : status;
}

}  // namespace fetic::app
