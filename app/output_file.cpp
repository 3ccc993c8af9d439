#include "app/output_file.hpp"

#include <fcntl.h>
#include <poll.h>
#include <sys/stat.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <future>
#include <iostream>
#include <memory>
#include <mutex>
#include <new>
#include <set>
#include <vector>

#include "app/exit_codes.hpp"
#include "app/interrupt.hpp"
#include "scenes/scene_error.hpp"

namespace fetic::app {
namespace {

std::string shown(const std::string& path) {
  return scenes::printable(path);
}

std::string reason(int error) {
  return std::strerror(error);
}

// ---- temporary files this process is writing, for clean-up on fatal paths ----

std::mutex temporaries_mutex;
std::set<std::string>& temporaries() {
  static std::set<std::string> names;
  return names;
}

void forget_temporary(const std::string& name) {
  std::lock_guard lock(temporaries_mutex);
  temporaries().erase(name);
}

// ---- what is at the path ----

enum class Kind { Stdout, Replace, Stream };

struct Target {
  Kind kind = Kind::Replace;
  std::string path;     // after following symbolic links
  bool exists = false;  // Replace: a regular file is there
  mode_t mode = 0;      // its permission bits
};

std::string parent_of(const std::string& path) {
  const size_t slash = path.rfind('/');
  if (slash == std::string::npos) return "";
  return path.substr(0, slash + 1);  // keeps the slash ("/" for the root)
}

// Follows symbolic links to the path they finally name (a dangling link names a file
// that does not exist yet: the output creates it).
std::string follow_links(const std::string& given) {
  std::string path = given;
  for (int hops = 0; hops < 40; ++hops) {
    struct stat info {};
    if (::lstat(path.c_str(), &info) != 0 || !S_ISLNK(info.st_mode)) return path;
    std::array<char, 4096> buffer{};
    const ssize_t length = ::readlink(path.c_str(), buffer.data(), buffer.size());
    if (length < 0 || static_cast<size_t>(length) >= buffer.size())
      throw OutputError(shown(given) + ": cannot follow the symbolic link (" +
                        reason(length < 0 ? errno : ENAMETOOLONG) + ")");
    const std::string target(buffer.data(), static_cast<size_t>(length));
    path = target.starts_with('/') ? target : parent_of(path) + target;
  }
  throw OutputError(shown(given) + ": cannot write: " + reason(ELOOP));
}

Target classify(const std::string& given) {
  if (given.empty()) throw OutputError("an output path is empty");
  if (is_stdout(given)) return {Kind::Stdout, given};
  Target target;
  target.path = follow_links(given);
  const std::string label =
      shown(given) + (target.path == given ? "" : " (-> " + shown(target.path) + ")");
  struct stat info {};
  if (::stat(target.path.c_str(), &info) != 0) {
    if (errno == ENOENT) return target;  // absent: created through a temporary file
    if (errno == ENOTDIR) throw OutputError(label + ": a part of the path is a file, not a folder");
    throw OutputError(label + ": cannot write (" + reason(errno) + ")");
  }
  if (S_ISREG(info.st_mode)) {
    target.exists = true;
    target.mode = info.st_mode & 07777;
    return target;
  }
  if (S_ISCHR(info.st_mode) || S_ISFIFO(info.st_mode)) {
    target.kind = Kind::Stream;
    return target;
  }
  if (S_ISDIR(info.st_mode))
    throw OutputError(label + ": is a directory; give the name of a file to write");
  if (S_ISBLK(info.st_mode))
    throw OutputError(label + ": is a block device; fetic writes no output onto a disk device");
  if (S_ISSOCK(info.st_mode)) throw OutputError(label + ": is a socket; fetic cannot write to it");
  throw OutputError(label + ": is not a file fetic can write");
}

// ---- writing ----

// Writes every byte or says why not ("" when all arrived). A signal that ends the run
// stops the waiting (EINTR; the handlers have no SA_RESTART).
std::string write_all(int fd, const char* data, size_t size, bool& interrupted_out) {
  while (size > 0) {
    const ssize_t n = ::write(fd, data, size);
    if (n > 0) {
      data += n;
      size -= static_cast<size_t>(n);
      continue;
    }
    if (n < 0 && errno == EINTR) {
      if (interrupted()) {
        interrupted_out = true;
        return std::string("interrupted by ") + interrupt_name();
      }
      continue;
    }
    if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK)) {  // a FIFO, a non-blocking stdout
      // Waits for room a tenth of a second at a time, asking for a stop in between (under
      // MPI that also takes in another process' stop notice).
      pollfd wait{fd, POLLOUT, 0};
      ::poll(&wait, 1, 100);
      if (interrupted()) {
        interrupted_out = true;
        return std::string("interrupted by ") + interrupt_name();
      }
      continue;
    }
    return n == 0 ? "the device accepted no more bytes" : reason(errno);
  }
  return "";
}

// Whole buffers written to a large file this process created go past the page cache
// (O_DIRECT) where the file system takes that: on this machine's VM the kernel's copy of a
// buffered write into the page cache (copy_folio_from_iter) took about 2.6 s of system
// CPU per GB, first touching fresh page-cache pages - 5 CPU-s of the 2.1 GB a 1e7 solve
// writes (docs/BENCHMARKS.md, "Outside set-up and solve") - against 0.2 s per GB direct.
// Only from the kDirectAfter-th whole buffer on: the outputs of ordinary size never
// change their way of writing. Every direct write is a whole aligned buffer at an aligned
// offset (all before it were whole buffers too); the first write that is not (the last,
// partial buffer, or any after a flush) or that does not complete in one call (a file
// system without O_DIRECT says EINVAL, a full disk writes short) turns the flag off for
// the rest of the file and is written, or written again, the ordinary way - so the bytes
// and every error are those of buffered writes.
class DirectWrites {
 public:
  static constexpr int kDirectAfter = 8;  // whole buffers written the ordinary way first
  // Only a regular file this process opened itself (never standard output: the flag
  // would change the shell's open file too).
  DirectWrites(int fd, bool own_file) : fd_(fd), allowed_(own_file) {}
  // Writes `size` bytes: directly when they are a whole buffer, otherwise (and after any
  // failure) through write_all.
  std::string write(const char* data, size_t size, bool whole_buffer, bool& interrupted_out) {
    if (!whole_buffer) allowed_ = false;
    if (allowed_ && !on_ && ++whole_buffers_ > kDirectAfter) start();
    if (on_ && whole_buffer) {
      const ssize_t n = ::write(fd_, data, size);
      if (n == static_cast<ssize_t>(size)) return "";
      if (n > 0) {  // written short: the rest the ordinary way
        data += n;
        size -= static_cast<size_t>(n);
      }
    }
    stop();
    return write_all(fd_, data, size, interrupted_out);
  }

 private:
  void start() {
    allowed_ = false;  // tried once
    struct stat info {};
    if (::fstat(fd_, &info) != 0 || !S_ISREG(info.st_mode)) return;
    const int flags = ::fcntl(fd_, F_GETFL);
    on_ = flags >= 0 && ::fcntl(fd_, F_SETFL, flags | O_DIRECT) == 0;
  }
  void stop() {
    if (!on_) return;
    on_ = false;
    const int flags = ::fcntl(fd_, F_GETFL);
    if (flags >= 0) (void)::fcntl(fd_, F_SETFL, flags & ~O_DIRECT);
  }
  int fd_;
  bool allowed_;  // may still start: a file of our own, nothing but whole buffers so far
  bool on_ = false;
  int whole_buffers_ = 0;
};

// An std::streambuf over a file descriptor that keeps the first failure. A full buffer is
// written by another thread while the next one fills (two buffers of 1 MiB, aligned for
// DirectWrites): writing then overlaps the formatting and compressing of the next bytes
// instead of following it (docs/BENCHMARKS.md, "Outputs at 1e7"). Bytes arrive in order:
// one write at a time.
class FdBuffer : public std::streambuf {
 public:
  // The buffers are not cleared: a small output makes only the pages it fills resident.
  FdBuffer(int fd, bool own_file) : direct_(fd, own_file) {
    for (std::unique_ptr<char[], Free>& buffer : buffers_)
      buffer.reset(static_cast<char*>(std::aligned_alloc(kAlignment, kSize)));
    if (!buffers_[0] || !buffers_[1]) throw std::bad_alloc();
    setp(buffers_[0].get(), buffers_[0].get() + kSize);
  }
  ~FdBuffer() override { wait(); }
  FdBuffer(const FdBuffer&) = delete;
  FdBuffer& operator=(const FdBuffer&) = delete;
  // Valid after sync() (the stream's flush), which waits for every byte.
  const std::string& error() const { return error_; }
  bool interrupted() const { return interrupted_; }

 protected:
  int_type overflow(int_type c) override {
    if (!hand_over()) return traits_type::eof();
    if (!traits_type::eq_int_type(c, traits_type::eof())) {
      *pptr() = traits_type::to_char_type(c);
      pbump(1);
    }
    return traits_type::not_eof(c);
  }
  int sync() override {
    const bool handed = hand_over();
    wait();
    return handed && error_.empty() ? 0 : -1;
  }

 private:
  static constexpr size_t kSize = size_t{1} << 20;
  static constexpr size_t kAlignment = 4096;  // O_DIRECT's, for any block size up to it
  struct Free {
    void operator()(char* buffer) const { std::free(buffer); }
  };

  // Waits for the write in flight; its failure becomes error_.
  void wait() {
    if (!writing_.valid()) return;
    writing_.get();
  }
  // Starts writing the filled buffer on the writer thread and fills the other meanwhile.
  bool hand_over() {
    const size_t filled = static_cast<size_t>(pptr() - pbase());
    wait();
    const char* data = pbase();
    current_ = 1 - current_;
    setp(buffers_[current_].get(), buffers_[current_].get() + kSize);
    if (!error_.empty()) return false;
    if (filled > 0)
      writing_ = std::async(std::launch::async, [this, data, filled] {
        error_ = direct_.write(data, filled, filled == kSize, interrupted_);
      });
    return true;
  }

  DirectWrites direct_;
  std::array<std::unique_ptr<char[], Free>, 2> buffers_;
  int current_ = 0;
  std::future<void> writing_;  // the write of the other buffer, while it runs
  std::string error_;          // written by the writer thread, read after wait()
  bool interrupted_ = false;
};

// Opens a device or FIFO for writing. A FIFO is opened without blocking - which fails
// (ENXIO) while it has no reader - and tried again every 50 ms until a reader comes or a
// stop is asked for (a signal, or under MPI another process' stop notice, which a blocking
// open could never take in). The FIFO stays non-blocking: write_all waits for room the
// same way. A device gets its blocking writes back.
int open_stream(const Target& target, const std::string& given) {
  while (true) {
    const int fd = ::open(target.path.c_str(), O_WRONLY | O_NOCTTY | O_CLOEXEC | O_NONBLOCK);
    if (fd >= 0) {
      struct stat info {};
      if (::fstat(fd, &info) == 0 && !S_ISFIFO(info.st_mode))
        (void)::fcntl(fd, F_SETFL, ::fcntl(fd, F_GETFL) & ~O_NONBLOCK);
      return fd;
    }
    const int error = errno;
    if (error != ENXIO && error != EINTR)
      throw OutputError(shown(given) + ": cannot open (" + reason(error) + ")");
    if (interrupted())
      throw OutputError(shown(given) + ": interrupted by " + interrupt_name() +
                            " while waiting to open it (a FIFO without a reader?)",
                        true);
    if (error == ENXIO) ::poll(nullptr, 0, 50);
  }
}

// Creates the temporary file beside `path`: NAME.tmpPID, or a shorter name when that
// one is too long for the directory.
int create_temporary(const std::string& path, mode_t mode, std::string& name) {
  const std::string pid = std::to_string(::getpid());
  static std::atomic<int> counter{0};
  std::string candidate = path + ".tmp" + pid;
  for (int attempt = 0; attempt < 100; ++attempt) {
    const int fd = ::open(candidate.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd >= 0) {
      if (mode != 0) (void)::fchmod(fd, mode);
      name = candidate;
      std::lock_guard lock(temporaries_mutex);
      temporaries().insert(name);
      return fd;
    }
    if (errno == EEXIST) {
      bool ours = false;
      {
        std::lock_guard lock(temporaries_mutex);
        ours = temporaries().count(candidate) > 0;
      }
      if (!ours && attempt == 0) {
        ::unlink(candidate.c_str());  // left by an earlier process that had our PID
        continue;
      }
      candidate = path + ".tmp" + pid + "." + std::to_string(++counter);
      continue;
    }
    if (errno == ENAMETOOLONG) {
      candidate = parent_of(path) + ".fetic.tmp" + pid + "." + std::to_string(++counter);
      continue;
    }
    if (errno == EINTR) continue;
    throw OutputError(shown(path) + ": cannot create the temporary file " + shown(candidate) +
                      " beside it (" + reason(errno) + ")");
  }
  throw OutputError(shown(path) + ": cannot create a temporary file beside it");
}

// An unnamed file in the directory of `path` (O_TMPFILE), so that a process killed while
// it writes (SIGKILL: mpirun ends its job so soon after forwarding a signal) leaves no
// temporary file behind; named (name_unnamed) only once written. -1 where the file system
// has no unnamed files: then create_temporary.
int create_unnamed(const std::string& path, mode_t mode) {
  const std::string parent = parent_of(path);
  int fd = -1;
  do {
    fd = ::open(parent.empty() ? "." : parent.c_str(), O_TMPFILE | O_WRONLY | O_CLOEXEC, 0666);
  } while (fd < 0 && errno == EINTR);
  if (fd >= 0 && mode != 0) (void)::fchmod(fd, mode);
  return fd;
}

// Links the written unnamed file `fd` beside `path` under a temporary name (to be renamed
// over `path`); false with errno set when it cannot.
bool name_unnamed(int fd, const std::string& path, std::string& name) {
  const std::string self = "/proc/self/fd/" + std::to_string(fd);
  const std::string pid = std::to_string(::getpid());
  static std::atomic<int> counter{0};
  std::string candidate = path + ".tmp" + pid;
  for (int attempt = 0; attempt < 100; ++attempt) {
    if (::linkat(AT_FDCWD, self.c_str(), AT_FDCWD, candidate.c_str(), AT_SYMLINK_FOLLOW) == 0) {
      name = candidate;
      std::lock_guard lock(temporaries_mutex);
      temporaries().insert(name);
      return true;
    }
    if (errno == EEXIST) {
      bool ours = false;  // an earlier version of this output still held for the commit
      {
        std::lock_guard lock(temporaries_mutex);
        ours = temporaries().count(candidate) > 0;
      }
      if (ours)
        candidate = path + ".tmp" + pid + "." + std::to_string(++counter);
      else
        ::unlink(candidate.c_str());  // left by an earlier process that had our PID
    } else if (errno == ENAMETOOLONG) {
      candidate = parent_of(path) + ".fetic.tmp" + pid + "." + std::to_string(++counter);
    } else if (errno != EINTR) {
      return false;
    }
  }
  return false;
}

void discard_temporary(const std::string& name) {
  ::unlink(name.c_str());
  forget_temporary(name);
}

void rename_into_place(const std::string& temporary, const std::string& path,
                       const std::string& given) {
  if (std::rename(temporary.c_str(), path.c_str()) != 0) {
    const int error = errno;
    discard_temporary(temporary);
    throw OutputError(shown(given) + ": cannot put the file in place (" + reason(error) + ")");
  }
  forget_temporary(temporary);
}

// ---- outputs waiting for PendingOutputs::commit ----

struct Staged {
  std::string temporary;
  std::string path;   // where it goes (links followed)
  std::string given;  // as the user named it, for messages
};

std::mutex pending_mutex;
bool pending_active = false;
std::vector<Staged>& pending() {
  static std::vector<Staged> files;
  return files;
}

// Adds the finished temporary to the pending outputs; false when none are being held.
bool hold(const std::string& temporary, const std::string& path, const std::string& given) {
  std::lock_guard lock(pending_mutex);
  if (!pending_active) return false;
  for (Staged& staged : pending())
    if (staged.path == path) {  // written again: the new version replaces the pending one
      discard_temporary(staged.temporary);
      staged = {temporary, path, given};
      return true;
    }
  pending().push_back({temporary, path, given});
  return true;
}

// A finished temporary: renamed into place now, or held for the commit.
void place(const std::string& temporary, const Target& target, const std::string& given) {
  if (!hold(temporary, target.path, given)) rename_into_place(temporary, target.path, given);
}

// "." for "name", "/" for "/name", "a/b" for "a/b/name".
std::string folder_of(const std::string& path) {
  const std::string parent = parent_of(path);
  if (parent.empty()) return ".";
  return parent.size() == 1 ? parent : parent.substr(0, parent.size() - 1);
}

std::string label_of(const std::string& given, const std::string& path) {
  return shown(given) + (path == given ? "" : " (-> " + shown(path) + ")");
}

// Throws unless `folder` is a folder this process can create files in.
void check_writable_folder(const std::string& folder, const std::string& label) {
  struct stat info {};
  if (::stat(folder.c_str(), &info) != 0)
    throw OutputError(label + ": cannot reach the folder " + shown(folder) + " (" + reason(errno) +
                      ")");
  if (!S_ISDIR(info.st_mode)) throw OutputError(label + ": " + shown(folder) + " is not a folder");
  if (::access(folder.c_str(), W_OK | X_OK) != 0)
    throw OutputError(label + ": cannot write in the folder " + shown(folder) + " (" +
                      reason(errno) + ")");
}

// Runs `write` on a descriptor: a temporary file renamed into place, the stream, or stdout.
void write_through(const std::string& given,
                   const std::function<std::pair<std::string, bool>(int fd)>& write) {
  const Target target = classify(given);
  std::string temporary;
  int fd = 1;
  bool unnamed = false;  // an O_TMPFILE file, named once written
  if (target.kind == Kind::Stdout) {
    std::cout.flush();  // the report printed before stays before the output
    std::fflush(stdout);
  } else if (target.kind == Kind::Stream) {
    fd = open_stream(target, given);
  } else {
    fd = create_unnamed(target.path, target.exists ? target.mode : 0);
    unnamed = fd >= 0;
    if (!unnamed) fd = create_temporary(target.path, target.exists ? target.mode : 0, temporary);
  }
  std::pair<std::string, bool> result;
  try {
    result = write(fd);
  } catch (...) {
    if (fd != 1) ::close(fd);
    if (!temporary.empty()) discard_temporary(temporary);
    throw;
  }
  auto [error, stopped] = result;
  if (unnamed && error.empty() && !name_unnamed(fd, target.path, temporary))
    error = "cannot name the written file beside it: " + reason(errno);
  if (fd != 1 && ::close(fd) != 0 && error.empty()) error = reason(errno);
  if (!error.empty()) {
    if (!temporary.empty()) discard_temporary(temporary);
    const std::string where = target.kind == Kind::Stdout ? "standard output" : shown(given);
    throw OutputError(where + ": cannot write (" + error + "); the output is lost or incomplete",
                      stopped);
  }
  if (!temporary.empty()) place(temporary, target, given);
}

}  // namespace

std::string resolved_output_path(const std::string& path) {
  return follow_links(path);
}

void check_output_file(const std::string& given) {
  const Target target = classify(given);
  if (target.kind != Kind::Replace) return;
  const std::string label = label_of(given, target.path);
  const std::string folder = folder_of(target.path);
  struct stat info {};
  if (::stat(folder.c_str(), &info) != 0 && (errno == ENOENT || errno == ENOTDIR))
    throw OutputError(label + ": the folder " + shown(folder) +
                      (target.path == given ? "" : " that the symbolic link points into") +
                      " does not exist");
  check_writable_folder(folder, label);
}

void check_output_folder(const std::string& given) {
  if (given.empty()) throw OutputError("an output folder's name is empty");
  if (is_stdout(given))
    throw OutputError("- (standard output) cannot take a folder of files; give a folder name");
  const std::string path = follow_links(given);
  const std::string label = label_of(given, path);
  struct stat info {};
  if (::stat(path.c_str(), &info) == 0) {
    if (!S_ISDIR(info.st_mode)) throw OutputError(label + ": is a file, not a folder");
    check_writable_folder(path, label);
    return;
  }
  if (path != given)
    throw OutputError(shown(given) + ": is a symbolic link to " + shown(path) +
                      ", which does not exist; give the name of a folder");
  // Missing: the nearest folder that exists must take the new ones.
  for (std::string folder = folder_of(path);; folder = folder_of(folder)) {
    if (::stat(folder.c_str(), &info) == 0) {
      if (!S_ISDIR(info.st_mode))
        throw OutputError(label + ": " + shown(folder) + " is a file, not a folder");
      check_writable_folder(folder, label);
      return;
    }
    if (folder == "." || folder == "/")
      throw OutputError(label + ": cannot reach the folder " + shown(folder) + " (" +
                        reason(errno) + ")");
  }
}

PendingOutputs::PendingOutputs() {
  std::lock_guard lock(pending_mutex);
  pending_active = true;
}

PendingOutputs::~PendingOutputs() {
  std::lock_guard lock(pending_mutex);
  for (const Staged& staged : pending())
    discard_temporary(staged.temporary);
  pending().clear();
  pending_active = false;
}

void PendingOutputs::commit() {
  std::vector<Staged> files;
  {
    std::lock_guard lock(pending_mutex);
    files.swap(pending());
  }
  for (size_t k = 0; k < files.size(); ++k)
    try {
      rename_into_place(files[k].temporary, files[k].path, files[k].given);
    } catch (const OutputError&) {
      for (size_t rest = k + 1; rest < files.size(); ++rest)
        discard_temporary(files[rest].temporary);
      throw;
    }
}

std::string current_version_of(const std::string& path) {
  const std::string target = follow_links(path);
  std::lock_guard lock(pending_mutex);
  if (pending_active)
    for (const Staged& staged : pending())
      if (staged.path == target) return staged.temporary;
  return path;
}

size_t PendingOutputs::size() const {
  std::lock_guard lock(pending_mutex);
  return pending().size();
}

void write_output(const std::string& path, std::string_view bytes) {
  write_through(path, [&](int fd) {
    bool stopped = false;
    std::string error = write_all(fd, bytes.data(), bytes.size(), stopped);
    return std::make_pair(error, stopped);
  });
}

void write_output(const std::string& path, const std::function<void(std::ostream&)>& write) {
  write_through(path, [&](int fd) {
    FdBuffer buffer(fd, fd != 1);
    std::ostream out(&buffer);
    write(out);
    out.flush();
    std::string error = buffer.error();
    if (error.empty() && !out) error = "the writer failed";
    return std::make_pair(error, buffer.interrupted());
  });
}

void write_output_by(const std::string& path,
                     const std::function<bool(const ExternalTarget&)>& write) {
  const Target target = classify(path);
  if (target.kind != Kind::Replace) {
    if (target.kind == Kind::Stdout) {
      std::cout.flush();
      std::fflush(stdout);
    }
    const ExternalTarget external{target.kind == Kind::Stdout ? "" : target.path, true};
    if (!write(external)) {
      const bool stopped = interrupted();
      throw OutputError((target.kind == Kind::Stdout ? "standard output" : shown(path)) +
                            (stopped ? std::string(": interrupted by ") + interrupt_name()
                                     : std::string(": writing failed")) +
                            "; the output is lost or incomplete",
                        stopped);
    }
    return;
  }
  std::string temporary;
  const int fd = create_temporary(target.path, target.exists ? target.mode : 0, temporary);
  ::close(fd);  // the program opens it by name
  bool ok = false;
  try {
    ok = write({temporary, false});
  } catch (...) {
    discard_temporary(temporary);
    throw;
  }
  if (!ok) {
    discard_temporary(temporary);
    const bool stopped = interrupted();
    throw OutputError(shown(path) +
                          (stopped ? std::string(": interrupted by ") + interrupt_name()
                                   : std::string(": writing failed")) +
                          "; nothing was written",
                      stopped);
  }
  place(temporary, target, path);
}

struct OutputStream::State {
  std::mutex mutex;
  int fd = -1;
  std::string name;
  std::string error;
};

OutputStream::OutputStream() : state_(std::make_unique<State>()) {}
OutputStream::~OutputStream() {
  close();
}

void OutputStream::open(const std::string& path) {
  close();
  const Target target = classify(path);
  int fd = 1;
  if (target.kind == Kind::Stream) {
    fd = open_stream(target, path);
  } else if (target.kind == Kind::Replace) {
    bool held = false;
    {
      std::lock_guard lock(pending_mutex);
      held = pending_active;
    }
    if (held) {  // into a temporary that the commit renames
      std::string temporary;
      fd = create_temporary(target.path, target.exists ? target.mode : 0, temporary);
      hold(temporary, target.path, path);
    } else {
      fd = ::open(target.path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
      if (fd < 0) throw OutputError(shown(path) + ": cannot open (" + reason(errno) + ")");
    }
  }
  std::lock_guard lock(state_->mutex);
  state_->fd = fd;
  state_->name = target.kind == Kind::Stdout ? "standard output" : shown(path);
  state_->error.clear();
}

bool OutputStream::is_open() const {
  return state_->fd >= 0;
}

void OutputStream::write(std::string_view bytes) {
  std::lock_guard lock(state_->mutex);
  if (state_->fd < 0 || !state_->error.empty()) return;
  bool stopped = false;
  const std::string error = write_all(state_->fd, bytes.data(), bytes.size(), stopped);
  if (!error.empty()) state_->error = state_->name + ": cannot write (" + error + ")";
}

std::string OutputStream::close() {
  std::lock_guard lock(state_->mutex);
  if (state_->fd > 1 && ::close(state_->fd) != 0 && state_->error.empty())
    state_->error = state_->name + ": cannot write (" + reason(errno) + ")";
  state_->fd = -1;
  return state_->error;
}

std::string OutputStream::error() const {
  std::lock_guard lock(state_->mutex);
  return state_->error;
}

int report_output_error(const OutputError& error) {
  std::cerr << error.what() << '\n';
  return error.interrupted() ? kExitInterrupted : kExitOutput;
}

int exit_status_of_writing(const std::function<void()>& write) {
  try {
    write();
  } catch (const OutputError& error) {
    return report_output_error(error);
  }
  return kExitOk;
}

void remove_temporary_outputs() noexcept {
  // try_lock: this may run while another thread holds the lock (it then stays).
  if (!temporaries_mutex.try_lock()) return;
  for (const std::string& name : temporaries())
    ::unlink(name.c_str());
  temporaries().clear();
  temporaries_mutex.unlock();
}

}  // namespace fetic::app
