#include "scenes/scene_text.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <vector>

namespace fetic::scenes {
namespace {

std::string mebibytes(double bytes) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f MiB", bytes / (1 << 20));
  return text;
}

SceneError read_error(const std::string& path, const std::string& message) {
  return SceneError(path, {{0, message}});
}

// Repeats a call interrupted by a signal, unless `stop` says the run ends.
template <class Call>
auto retrying(Call call, const std::function<bool()>& stop, const std::string& path,
              const char* waiting) {
  while (true) {
    const auto result = call();
    if (result >= 0 || errno != EINTR) return result;
    if (stop && stop())
      throw read_error(path, std::string("interrupted by a signal while ") + waiting);
  }
}

}  // namespace

std::string read_text_file(const std::string& path, std::size_t max_bytes, const std::string& what,
                           const std::function<bool()>& stop) {
  const std::string limit_text = "the limit for a " + what + " is " +
                                 mebibytes(static_cast<double>(max_bytes)) + " (" +
                                 std::to_string(max_bytes) + " bytes)";
  const int fd =
      retrying([&] { return ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NOCTTY); }, stop, path,
               ("opening the " + what + " (a FIFO without a writer?)").c_str());
  if (fd < 0) throw read_error(path, "cannot open the " + what + " (" + std::strerror(errno) + ")");
  struct Closer {
    int fd;
    ~Closer() { ::close(fd); }
  } closer{fd};
  struct stat info {};
  if (::fstat(fd, &info) != 0)
    throw read_error(path, "cannot read the " + what + " (" + std::strerror(errno) + ")");
  if (S_ISDIR(info.st_mode)) throw read_error(path, "is a directory, not a " + what);
  const bool regular = S_ISREG(info.st_mode);
  if (regular && static_cast<unsigned long long>(info.st_size) > max_bytes)
    throw read_error(path, "the file has " + mebibytes(static_cast<double>(info.st_size)) + " (" +
                               std::to_string(info.st_size) + " bytes); " + limit_text);
  // A regular file is read to its size (plus one byte, to see it growing); any other
  // stream in blocks, up to one byte beyond the limit.
  std::string text;
  text.resize(regular ? static_cast<size_t>(info.st_size) + 1 : size_t{1} << 16);
  size_t used = 0;
  while (true) {
    if (used == text.size()) {
      if (used > max_bytes) break;
      text.resize(std::min(text.size() * 2, max_bytes + 1));
    }
    const ssize_t n = retrying([&] { return ::read(fd, text.data() + used, text.size() - used); },
                               stop, path, ("reading the " + what).c_str());
    if (n < 0)
      throw read_error(path, "cannot read the " + what + " (" + std::strerror(errno) + ")");
    if (n == 0) break;
    used += static_cast<size_t>(n);
  }
  if (used > max_bytes)
    throw read_error(path, std::string(regular ? "the file grew while it was read and has "
                                               : "the stream gave ") +
                               "more than " + std::to_string(max_bytes) + " bytes; " + limit_text);
  text.resize(used);
  return text;
}

std::string read_scene_text(const std::string& path, const std::function<bool()>& stop) {
  return read_text_file(path, kMaxSceneFileBytes, "scene file", stop);
}

}  // namespace fetic::scenes
