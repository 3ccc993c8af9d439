#include "app/atomic_file.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>

namespace fetic::app {
namespace {

std::string temporary_name(const std::string& path) {
  return path + ".tmp" + std::to_string(::getpid());
}

void rename_into_place(const std::string& temporary, const std::string& path) {
  if (std::rename(temporary.c_str(), path.c_str()) != 0) {
    const std::string reason = std::strerror(errno);
    std::remove(temporary.c_str());
    throw OutputError(path + ": cannot write the file (" + reason + ")");
  }
}

}  // namespace

void write_via_temporary(const std::string& path,
                         const std::function<bool(const std::string&)>& write) {
  const std::string temporary = temporary_name(path);
  bool ok = false;
  try {
    ok = write(temporary);
  } catch (...) {
    std::remove(temporary.c_str());
    throw;
  }
  if (!ok) {
    const std::string reason = errno ? std::strerror(errno) : "write failed";
    std::remove(temporary.c_str());
    throw OutputError(path + ": cannot write the file (" + reason + ")");
  }
  rename_into_place(temporary, path);
}

void write_file_atomically(const std::string& path,
                           const std::function<void(std::ostream&)>& write) {
  write_via_temporary(path, [&](const std::string& temporary) {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    if (!out) return false;
    write(out);
    out.flush();
    return static_cast<bool>(out);
  });
}

}  // namespace fetic::app
