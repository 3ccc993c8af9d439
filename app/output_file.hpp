#pragma once
// Every output of every command goes through here, so that what is at the path is never
// destroyed by mistake, no reader sees half a file, and no lost byte passes unreported.
//
// Where an output goes (docs/RELIABILITY.md, "Output targets"):
// * "-": standard output, written directly.
// * A path that does not exist yet, or a regular file: written to NAME.tmpPID beside it,
//   then renamed over it (an existing file keeps its permission bits).
// * A character device (/dev/null, a terminal) or a FIFO: opened and written directly.
// * A symbolic link: followed to the path it finally names, which is then treated as
//   above; the link itself stays.
// * A directory, a block device or a socket: refused.
// Every write and the close are checked. Any failure throws OutputError naming the path
// and the reason; the command then exits with status 5 (130 when a signal ended it).
//
// A command with several outputs checks every target before the work starts
// (check_output_file, check_output_folder) and holds a PendingOutputs while it writes:
// the files then stay in their temporaries until commit() renames them all, so a run
// that fails half-way (an output that cannot be written, a lost monitor line) replaces
// no existing file.

#include <functional>
#include <memory>
#include <ostream>
#include <stdexcept>
#include <string>
#include <string_view>

namespace fetic::app {

class OutputError : public std::runtime_error {
 public:
  explicit OutputError(const std::string& message, bool interrupted = false)
      : std::runtime_error(message), interrupted_(interrupted) {}
  // SIGINT or SIGTERM arrived while waiting on the target (e.g. a FIFO without reader).
  bool interrupted() const { return interrupted_; }

 private:
  bool interrupted_;
};

// Writes the whole output at once.
void write_output(const std::string& path, std::string_view bytes);
// The same for a writer that streams into an std::ostream.
void write_output(const std::string& path, const std::function<void(std::ostream&)>& write);

// For a program that writes the output itself (ffmpeg). `write` gets the file to write
// to - a temporary file, the device or FIFO itself, or "" for standard output (then the
// program must write to its file descriptor 1) - and whether that file is a stream (not
// seekable). It returns false when the program failed.
struct ExternalTarget {
  std::string file;  // "" means standard output
  bool stream = false;
};
void write_output_by(const std::string& path,
                     const std::function<bool(const ExternalTarget&)>& write);

// An output written a line at a time while the command runs (a log such as the state
// file of `fetic gui`): it cannot appear atomically, so a regular file is truncated and
// written in place; other targets as above. Thread-safe; every write is checked.
class OutputStream {
 public:
  OutputStream();  // not copyable: it owns its open target (state_)
  ~OutputStream();
  // Throws OutputError when the target cannot be opened.
  void open(const std::string& path);
  bool is_open() const;
  // Appends the bytes; after the first failure writes nothing more.
  void write(std::string_view bytes);
  // Closes (checked); returns the first failure, or "" when every byte arrived.
  std::string close();
  // The first failure so far ("" when none).
  std::string error() const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

// ---- checked before the work starts ----

// The path that a chain of symbolic links finally names (for a dangling link, the path it
// names, which does not exist yet); `path` itself when it is no link. Throws OutputError
// for a loop.
std::string resolved_output_path(const std::string& path);

// Throws OutputError unless `path` can take a file: "-", a character device or FIFO, or a
// regular file, existing or not, in an existing folder this process can write in (links
// followed). A directory, a missing folder, a dangling link into a missing folder are
// refused with a message saying which.
void check_output_file(const std::string& path);

// The same for a folder that is to hold files (--vtu, render --out): an existing folder
// this process can write in, or a path whose missing folders can be created (the nearest
// existing one is a writable folder; none of the way is a file).
void check_output_folder(const std::string& path);

// ---- committed together ----

// While one is alive, every output that goes to a regular file (write_output,
// write_output_by, OutputStream) stays in its temporary file, and commit() renames them
// all into place at the end; destroyed without commit() it removes them, and no existing
// file is replaced. Writing the same path again replaces the earlier pending version.
// Outputs to "-", devices and FIFOs are streams and are written at once. One per process
// at a time (the PNG encoder threads of `render` write through it).
class PendingOutputs {
 public:
  PendingOutputs();
  ~PendingOutputs();
  PendingOutputs(const PendingOutputs&) = delete;
  PendingOutputs& operator=(const PendingOutputs&) = delete;
  // Renames every pending file into place; throws OutputError when one cannot be (the
  // rest are then removed).
  void commit();
  // How many files wait.
  size_t size() const;
};

// Where the latest version of an output is now: its temporary file while a PendingOutputs
// holds it, otherwise `path` itself (so a file grown a piece at a time, the .pvd of a
// series, is grown where it waits).
std::string current_version_of(const std::string& path);

// True when `path` means standard output; commands then print their report to stderr so
// that the output stays clean.
inline bool is_stdout(const std::string& path) {
  return path == "-";
}

// Prints the error and returns the exit status it means (5, or 130 when interrupted).
int report_output_error(const OutputError& error);

// Runs `write` and returns the command's exit status: 0, or report_output_error's for the
// OutputError it threw (a command whose last step is writing its output).
int exit_status_of_writing(const std::function<void()>& write);

// Removes the temporary files this process is writing (for the out-of-memory and
// terminate paths, which end the process without unwinding).
void remove_temporary_outputs() noexcept;

}  // namespace fetic::app
