#include "app/movie_stream.hpp"

#include <fcntl.h>
#include <poll.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstring>
#include <string>
#include <vector>

#include "app/child_process.hpp"
#include "app/interrupt.hpp"

extern char** environ;

namespace fetic::app {
namespace {

// The pipe's write end is non-blocking: while ffmpeg takes no input (it may wait to open
// a FIFO without a reader), the writer looks at the interrupt flag every 100 ms instead of
// sleeping in write(), where a signal delivered to another thread would not wake it.
bool write_all(int fd, const std::uint8_t* data, std::size_t size) {
  while (size > 0) {
    const ssize_t n = ::write(fd, data, size);
    if (n < 0) {
      if (interrupted()) return false;
      if (errno == EAGAIN) {
        pollfd ready{fd, POLLOUT, 0};
        ::poll(&ready, 1, 100);
        continue;
      }
      if (errno == EINTR) continue;
      return false;
    }
    data += n;
    size -= static_cast<std::size_t>(n);
  }
  return true;
}

}  // namespace

int spawn_ffmpeg(const std::vector<std::string>& input, const std::vector<std::string>& encoding,
                 const ExternalTarget& target, int stdin_fd, pid_t& child) {
  std::vector<std::string> arguments{"ffmpeg", "-y", "-loglevel", "error"};
  arguments.insert(arguments.end(), input.begin(), input.end());
  arguments.insert(arguments.end(), {"-c:v", "libx264"});
  arguments.insert(arguments.end(), encoding.begin(), encoding.end());
  // yuv420p for players; the pad makes odd sizes even, as H.264 needs.
  arguments.insert(arguments.end(),
                   {"-pix_fmt", "yuv420p", "-vf", "pad=ceil(iw/2)*2:ceil(ih/2)*2", "-f", "mp4"});
  // A stream cannot be rewound to write the index at the front: a fragmented mp4.
  if (target.stream) arguments.insert(arguments.end(), {"-movflags", "frag_keyframe+empty_moov"});
  // "file:" keeps a ':' in the name from being read as a protocol.
  arguments.push_back(target.file.empty() ? "pipe:1" : "file:" + target.file);
  std::vector<char*> argv;
  for (std::string& argument : arguments)
    argv.push_back(argument.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  if (stdin_fd >= 0) posix_spawn_file_actions_adddup2(&actions, stdin_fd, 0);  // clears CLOEXEC
  // fetic ignores SIGPIPE (a lost write is reported, not fatal: a frame written after
  // ffmpeg stopped fails with EPIPE); ffmpeg gets the default.
  posix_spawnattr_t attributes;
  posix_spawnattr_init(&attributes);
  sigset_t defaults;
  sigemptyset(&defaults);
  sigaddset(&defaults, SIGPIPE);
  posix_spawnattr_setsigdefault(&attributes, &defaults);
  posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETSIGDEF);
  const int spawned = posix_spawnp(&child, "ffmpeg", &actions, &attributes, argv.data(), environ);
  posix_spawnattr_destroy(&attributes);
  posix_spawn_file_actions_destroy(&actions);
  return spawned;
}

MovieStream::MovieStream(const ExternalTarget& target, int width, int height, int fps)
    : width_(width), height_(height) {
  const std::string shown = target.file.empty() ? "standard output" : target.file;
  int fds[2];
  if (::pipe2(fds, O_CLOEXEC) != 0)
    throw OutputError(shown + ": cannot open a pipe to ffmpeg (" + std::strerror(errno) + ")");
  ::fcntl(fds[1], F_SETFL, O_NONBLOCK);  // fetic's end only (see write_all)
  // A frame is megabytes: a 1 MiB pipe (the unprivileged maximum) instead of 64 KiB takes
  // it in a few writes rather than dozens of poll-and-write rounds. Best effort.
  ::fcntl(fds[1], F_SETPIPE_SZ, 1 << 20);
  const std::string size = std::to_string(width) + "x" + std::to_string(height);
  // veryfast: about twice the speed of x264's default preset, and on these flat pictures
  // no larger.
  const int spawned = spawn_ffmpeg({"-f", "rawvideo", "-pix_fmt", "rgba", "-s", size, "-framerate",
                                    std::to_string(fps), "-i", "pipe:0"},
                                   {"-preset", "veryfast"}, target, fds[0], child_);
  ::close(fds[0]);
  if (spawned != 0) {
    ::close(fds[1]);
    child_ = 0;
    throw OutputError(shown + ": cannot start ffmpeg (" + std::strerror(spawned) + ")");
  }
  pipe_ = fds[1];
  writer_ = std::thread([this] { write_frames(); });
}

MovieStream::~MovieStream() {
  {
    std::lock_guard lock(mutex_);
    closing_ = true;
    broken_ = true;  // drop what is still queued
  }
  changed_.notify_all();
  if (writer_.joinable()) writer_.join();
  if (pipe_ >= 0) ::close(pipe_);
  if (child_ > 0) stop_ffmpeg();
}

void MovieStream::write_frames() {
  std::unique_lock lock(mutex_);
  for (;;) {
    changed_.wait(lock, [&] { return closing_ || !queue_.empty(); });
    if (queue_.empty() || broken_) return;
    render::Image image = std::move(queue_.front());
    queue_.pop_front();
    changed_.notify_all();
    lock.unlock();
    const bool ok = write_all(pipe_, image.rgba.data(), image.rgba.size());
    lock.lock();
    if (!ok) {
      broken_ = true;
      changed_.notify_all();
      return;
    }
    ++written_;
  }
}

void MovieStream::submit(render::Image image) {
  if (image.width != width_ || image.height != height_)
    throw OutputError("a frame of " + std::to_string(image.width) + "x" +
                      std::to_string(image.height) + " pixels in a movie of " +
                      std::to_string(width_) + "x" + std::to_string(height_));
  std::unique_lock lock(mutex_);
  changed_.wait(lock, [&] { return broken_ || queue_.size() < 2; });
  if (broken_) throw OutputError("ffmpeg stopped taking frames");
  queue_.push_back(std::move(image));
  changed_.notify_all();
}

bool MovieStream::finish() {
  {
    std::lock_guard lock(mutex_);
    closing_ = true;
    if (interrupted()) broken_ = true;
  }
  changed_.notify_all();
  writer_.join();
  ::close(pipe_);  // end of input: ffmpeg writes the file's index and exits
  pipe_ = -1;
  if (broken_ || interrupted()) {
    stop_ffmpeg();
    return false;
  }
  // SIGINT/SIGTERM interrupt waitpid (no SA_RESTART): stop ffmpeg then, and wait for it,
  // so that its file is removed only once nobody writes it any more.
  int status = 0;
  while (::waitpid(child_, &status, 0) < 0) {
    if (errno != EINTR) {
      child_ = 0;
      return false;
    }
    if (interrupted()) {
      stop_ffmpeg();
      return false;
    }
  }
  child_ = 0;
  errno = 0;
  return !interrupted() && WIFEXITED(status) && WEXITSTATUS(status) == 0;
}

void MovieStream::stop_ffmpeg() {
  stop_child(child_);
  child_ = 0;
}

}  // namespace fetic::app
