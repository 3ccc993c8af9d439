#pragma once
// The monitor stream of `fetic solve --monitor FILE` (docs/COMMANDS.md, "Monitor stream"):
// one JSON object per line and per iteration, written as the iteration ends (each line is
// one write, so a reader following a FIFO, a pipe or a growing file sees whole lines at
// once) - load factor, iteration, residual, working-set size, the contact pairs that
// entered and left the working set since the previous line, seconds since the solve
// began, and with --monitor-full N the state (displacements, contact multipliers) every
// N-th iteration. The entries equal the result file's `history` entry for entry.
// `fetic gui --monitor FILE` writes the same lines for every solve the window performs
// (each a new load factor starting at iteration 0; the model may change on a reload).

#include <chrono>
#include <string>
#include <vector>

#include "app/output_file.hpp"
#include "solver/method.hpp"

namespace CLI {
class App;
}

namespace fetic::app {

// --monitor FILE|- and --monitor-full [N] (fetic solve, fetic gui); `path_help` says what
// the stream covers for the command.
void add_monitor_options(CLI::App* command, std::string& path, int& full_every,
                         const std::string& path_help);

class SolveMonitor {
 public:
  // `full_every` > 0 adds the state every that many iterations. `writes`: false on the
  // processes of a distributed solve that are not rank 0 (they still take part in the
  // collective gathers of the state, which every process must call alike).
  SolveMonitor(const solver::Model& model, int full_every, bool writes);
  // Opens the target (throws OutputError, see output_file.hpp).
  void open(const std::string& path);
  // Before each load factor of a sweep.
  void begin_load(double load_factor);
  // Before a solve of another model (the window reloaded its scene file).
  void begin_load(double load_factor, const solver::Model& model);
  // After the start (history entry 0) and after each iteration: writes the new entries.
  void observe(const solver::Method& method);
  // Closes the target; returns the first write failure ("" when every line arrived).
  std::string close();

 private:
  const solver::Model* model_;
  int full_every_;
  bool writes_;
  OutputStream out_;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
  double load_factor_ = 0.0;
  size_t written_ = 0;             // history entries of this load factor written
  std::vector<char> working_set_;  // per contact pair, as of the last line
  bool header_written_ = false;    // the first line: version and units
};

}  // namespace fetic::app
