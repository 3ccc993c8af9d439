#pragma once
// Runs fetic as a child process with chosen standard streams (a file, a private device
// node, a closed descriptor), captures what it prints and lets a test signal it. Header
// only: the app tests use it without linking the program's libraries.

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <sys/sysmacros.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

extern char** environ;

namespace fetic::test {

// A private temporary folder, removed with everything in it.
class TempDir {
 public:
  TempDir() {
    static std::atomic<int> counter{0};
    path_ = std::filesystem::temp_directory_path() /
            ("fetic_test_" + std::to_string(::getpid()) + "_" + std::to_string(++counter));
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  std::string operator/(const std::string& name) const { return (path_ / name).string(); }
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

inline std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

// Device nodes need root (CAP_MKNOD); tests skip themselves otherwise.
inline bool can_make_devices() {
  return ::geteuid() == 0;
}

// A private character device in `dir` with the numbers of the null (1,3) or full (1,7)
// device: the test never touches the machine's own /dev entries.
inline std::string make_char_device(const TempDir& dir, const std::string& name, int major,
                                    int minor) {
  const std::string path = dir / name;
  if (::mknod(path.c_str(), S_IFCHR | 0666, makedev(major, minor)) != 0)
    throw std::runtime_error("mknod " + path + " failed");
  return path;
}

inline bool is_char_device(const std::string& path) {
  struct stat info {};
  return ::lstat(path.c_str(), &info) == 0 && S_ISCHR(info.st_mode);
}
inline bool is_fifo(const std::string& path) {
  struct stat info {};
  return ::lstat(path.c_str(), &info) == 0 && S_ISFIFO(info.st_mode);
}
inline bool is_symlink(const std::string& path) {
  struct stat info {};
  return ::lstat(path.c_str(), &info) == 0 && S_ISLNK(info.st_mode);
}

struct Streams {
  std::string stdout_path;               // "" : captured
  bool close_stdout = false;             // start with descriptor 1 closed
  std::string stdin_path;                // "" : inherited
  std::vector<std::string> environment;  // extra NAME=VALUE entries
  std::string shell_prefix;  // run through sh -c "PREFIX; exec fetic ..." (e.g. ulimit -v N)
};

struct Result {
  int status = -1;  // exit status, or -1 when killed by a signal
  int signal = 0;
  std::string out, err;
};

// A running fetic; wait() collects it.
class Process {
 public:
  Process(const std::vector<std::string>& arguments, const Streams& streams = {})
      : out_(dir_ / "stdout"), err_(dir_ / "stderr") {
    std::vector<std::string> argv;
    if (streams.shell_prefix.empty()) {
      argv.push_back(FETIC_EXECUTABLE);
      argv.insert(argv.end(), arguments.begin(), arguments.end());
    } else {
      std::string command = streams.shell_prefix + "; exec '" + std::string(FETIC_EXECUTABLE) + "'";
      for (const std::string& a : arguments)
        command += " '" + a + "'";
      argv = {"/bin/sh", "-c", command};
    }
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    if (!streams.stdin_path.empty())
      posix_spawn_file_actions_addopen(&actions, 0, streams.stdin_path.c_str(), O_RDONLY, 0);
    if (streams.close_stdout)
      posix_spawn_file_actions_addclose(&actions, 1);
    else if (!streams.stdout_path.empty())
      posix_spawn_file_actions_addopen(&actions, 1, streams.stdout_path.c_str(), O_WRONLY, 0);
    else
      posix_spawn_file_actions_addopen(&actions, 1, out_.c_str(), O_WRONLY | O_CREAT | O_TRUNC,
                                       0644);
    posix_spawn_file_actions_addopen(&actions, 2, err_.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    std::vector<std::string> environment;
    for (char** e = environ; *e; ++e)
      environment.emplace_back(*e);
    environment.insert(environment.end(), streams.environment.begin(), streams.environment.end());
    std::vector<char*> env, args;
    for (std::string& e : environment)
      env.push_back(e.data());
    env.push_back(nullptr);
    for (std::string& a : argv)
      args.push_back(a.data());
    args.push_back(nullptr);
    const int failed = posix_spawn(&pid_, args[0], &actions, nullptr, args.data(), env.data());
    posix_spawn_file_actions_destroy(&actions);
    if (failed) throw std::runtime_error("cannot start " + argv[0]);
  }
  ~Process() {
    if (pid_ > 0) {
      ::kill(pid_, SIGKILL);
      ::waitpid(pid_, nullptr, 0);
    }
  }
  Process(const Process&) = delete;
  Process& operator=(const Process&) = delete;

  void signal(int number) const { ::kill(pid_, number); }

  // Waits (up to 60 s) until the program has installed its SIGINT/SIGTERM handlers, so
  // that a signal is its to handle and does not kill it during start-up.
  bool wait_for_signal_handlers() const {
    return wait_until([&] {
      std::ifstream in("/proc/" + std::to_string(pid_) + "/status");
      for (std::string line; std::getline(in, line);)
        if (line.rfind("SigCgt:", 0) == 0) {
          const unsigned long long caught = std::stoull(line.substr(7), nullptr, 16);
          return (caught >> (SIGINT - 1) & 1) && (caught >> (SIGTERM - 1) & 1);
        }
      return false;
    });
  }

  // Waits (up to 60 s) until the program blocks opening a FIFO that has no other end:
  // the kernel's wait channel says so (wait_for_partner); where it is hidden, the open
  // system call seen in three polls 50 ms apart, once the signal handlers are in place.
  bool wait_for_fifo_open() const {
    if (!wait_for_signal_handlers()) return false;
    int seen = 0;
    return wait_until([&] { return blocked_opening_fifo(pid_, seen); });
  }

  // The same for a child of the program (ffmpeg writing the movie); its process id, or -1
  // after 60 s.
  pid_t wait_for_child_fifo_open() const {
    if (!wait_for_signal_handlers()) return -1;
    pid_t child = -1;
    int seen = 0;
    const bool blocked = wait_until([&] {
      std::ifstream children("/proc/" + std::to_string(pid_) + "/task/" + std::to_string(pid_) +
                             "/children");
      pid_t first = -1;
      if (!(children >> first)) return false;
      if (first != child) seen = 0;
      child = first;
      return blocked_opening_fifo(child, seen);
    });
    return blocked ? child : -1;
  }
  std::string stderr_so_far() const { return read_text(err_); }

  // Waits up to `timeout` (then kills it and fails the result: status -1, signal 9).
  Result wait(std::chrono::seconds timeout = std::chrono::seconds(120)) {
    Result result;
    int raw = 0;
    const auto end = std::chrono::steady_clock::now() + timeout;
    while (::waitpid(pid_, &raw, WNOHANG) == 0) {
      if (std::chrono::steady_clock::now() > end) {
        ::kill(pid_, SIGKILL);
        ::waitpid(pid_, &raw, 0);
        break;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    pid_ = -1;
    if (WIFEXITED(raw)) result.status = WEXITSTATUS(raw);
    if (WIFSIGNALED(raw)) result.signal = WTERMSIG(raw);
    result.out = read_text(out_);
    result.err = read_text(err_);
    return result;
  }

 private:
  // One poll: the process waits to open a FIFO - blocked in the open (a scene FIFO), or,
  // for an output, in the pause between two non-blocking opens (poll(NULL, 0, 50) in
  // app/output_file.cpp). `seen` counts polls in a row that saw the open system call
  // where the wait channel is hidden, or that pause.
  static bool blocked_opening_fifo(pid_t pid, int& seen) {
    std::ifstream wchan("/proc/" + std::to_string(pid) + "/wchan");
    std::string where;
    wchan >> where;
    if (where == "wait_for_partner") return true;
    std::ifstream syscall("/proc/" + std::to_string(pid) + "/syscall");
    long current = -1;
    unsigned long fds = 1, count = 1;
    syscall >> current >> std::hex >> fds >> count;
    const bool pausing = current == SYS_poll && fds == 0 && count == 0;
    const bool opening = (where == "0" || where.empty()) && current == SYS_openat;
    seen = pausing || opening ? seen + 1 : 0;
    std::this_thread::sleep_for(std::chrono::milliseconds(40));
    return seen >= 3;
  }

  template <class Condition>
  static bool wait_until(Condition condition) {
    const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    while (std::chrono::steady_clock::now() < end) {
      if (condition()) return true;
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    return false;
  }

  TempDir dir_;
  std::string out_, err_;
  pid_t pid_ = -1;
};

inline Result run_fetic(const std::vector<std::string>& arguments, const Streams& streams = {}) {
  return Process(arguments, streams).wait();
}

inline std::string bundled_scene(const std::string& name) {
  return std::string(FETIC_BUNDLED_SCENES_DIR) + "/" + name;
}

}  // namespace fetic::test
