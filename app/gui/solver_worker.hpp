#pragma once
// The solver thread of `fetic gui`. The UI never touches a method: it states what it wants
// (model, method, load factor) and the worker re-solves, warm-started, publishing an
// immutable SolveState after every iteration. A newer request abandons the current solve
// between two iterations, so dragging the load slider never waits for a solve to finish.
// A solve can be cancelled, and in live stepping the worker performs only as many
// iterations as the UI allows (Step and Play advance the solver itself).

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "render/frame_sequence.hpp"
#include "solver/load_sweep.hpp"
#include "solver/method.hpp"
#include "solver/model.hpp"

namespace fetic::app::gui {

// What one solve has produced so far; never changed once published.
struct SolveState {
  std::shared_ptr<const solver::Model> model;
  std::uint64_t model_generation = 0;
  std::uint64_t request = 0;  // the load request this solve answers
  double load_factor = 0.0;
  solver::MethodKind method = solver::MethodKind::FetiC;
  solver::Preconditioner preconditioner = solver::Preconditioner::Dirichlet;
  std::vector<std::shared_ptr<const solver::Snapshot>> iterates;  // iteration 0 .. now
  std::vector<solver::HistoryEntry> history;
  bool finished = false;   // converged, failed or cancelled
  bool cancelled = false;  // stopped by cancel() before it converged
  solver::Status status = solver::Status::Running;
  std::string message;
  double solve_seconds = 0.0;
  std::chrono::steady_clock::time_point finished_at{};  // when the solve ended
  // Scales for the whole slider range: a survey of the solve at the largest load factor.
  std::shared_ptr<const render::RunExtent> extent;
  double max_load = 2.0;  // top of the load slider (the target's, or chosen from the scene)
  std::string error;      // the method could not be set up for this model
};

struct SolverTarget {
  std::shared_ptr<const solver::Model> model;
  std::uint64_t model_generation = 0;
  solver::MethodKind method = solver::MethodKind::FetiC;
  solver::SolveOptions options;
  double max_load = 0.0;  // top of the load slider; 0: automatic_max_load()
  double load_factor = 1.0;
  std::uint64_t request = 0;
  // Live stepping: the solve starts at iteration 0 and advances only as far as
  // SolverWorker::allow() lets it.
  bool live = false;
};

// What the worker is doing right now, for a progress display.
struct WorkerProgress {
  bool surveying = false;  // solving at the slider's top for the fixed scales
  bool paused = false;     // live stepping: waiting for allow()
  int iteration = 0;
  double residual = 0.0;
  int active_set = 0;
};

// The top of the load slider when none is given: twice the scene's loads; when nothing
// touches at the scene's loads (`at_one`: converged solve at load factor 1 with an empty
// working set, so displacements grow linearly with the load), twice the load factor at
// which the first contact closes, rounded up to 1, 2 or 5 x 10^k.
double automatic_max_load(const solver::Model& model, const solver::Snapshot& at_one);

class SolverWorker {
 public:
  // `wake` is called (from the worker thread) after each publication, e.g. to wake the UI.
  explicit SolverWorker(std::function<void()> wake);
  ~SolverWorker();
  SolverWorker(const SolverWorker&) = delete;
  SolverWorker& operator=(const SolverWorker&) = delete;

  // Replaces what is to be solved; cheap, returns at once.
  void request(const SolverTarget& target);
  // The newest published state (null before the first).
  std::shared_ptr<const SolveState> latest() const;
  // True while a request has not been answered by a finished solve.
  bool busy() const;
  // Waits at most `budget` for a finished solve answering `request` (or a later one);
  // returns it, or the newest state when the time is up.
  std::shared_ptr<const SolveState> wait_for(std::uint64_t request,
                                             std::chrono::microseconds budget) const;
  // Stops the current solve (or survey) between two iterations; it is published finished
  // and cancelled. The next request solves again, warm from where it stopped.
  void cancel();
  // Live stepping: the current solve may go up to iteration `iterations` (-1: to the end).
  // A request with `live` set starts at 0; one without, at -1.
  void allow(int iterations);
  // True while a live solve waits for allow().
  bool paused() const;
  WorkerProgress progress() const;
  // Called on the worker thread when a solve has started (`started`, history entry 0) and
  // after each of its iterations - not for the survey solves that fix the picture's
  // scales: the window's --monitor stream. Clearing it (nullptr) waits for a call in
  // progress, so that what it writes to can be closed afterwards.
  using Observer = std::function<void(const solver::Model&, const solver::Method&,
                                      double load_factor, bool started)>;
  void observe_with(Observer observer);

 private:
  void notify_observer(const solver::Model& model, const solver::Method& method, double load_factor,
                       bool started);
  // What the worker thread has set up for the current model and method.
  struct Setup {
    std::unique_ptr<solver::Method> method;
    std::unique_ptr<solver::SweepDriver> driver;  // the warm starts of method
    std::shared_ptr<const solver::Model> model;   // keeps the method's model alive
    std::uint64_t generation = 0;
    solver::MethodKind kind{};
    solver::SolveOptions options;
    double max_load = -1.0;  // the target's max_load surveyed; -1: none yet
    double slider_max = 2.0;
    std::shared_ptr<const render::RunExtent> extent;
    std::string error;  // the method could not be set up
  };
  void run();
  bool next_target(SolverTarget& target);
  static bool needs_remake(const Setup& setup, const SolverTarget& target);
  static void make_method(Setup& setup, const SolverTarget& target);
  bool survey_scales(Setup& setup, const SolverTarget& target);
  void solve(Setup& setup, SolverTarget target);
  void mark_idle();
  bool superseded() const;
  void publish(std::shared_ptr<const SolveState> state);
  bool cancel_requested() const;
  // Live stepping: waits until `iteration` is below the allowance; false when the solve
  // is superseded or cancelled meanwhile.
  bool wait_for_allowance(int iteration);
  void set_progress(const WorkerProgress& progress);
  void publish_cancelled_survey(const SolverTarget& target);

  std::function<void()> wake_;
  mutable std::mutex mutex_;
  std::condition_variable changed_;
  mutable std::condition_variable published_;
  SolverTarget target_;
  std::uint64_t version_ = 0;  // bumped by every request()
  std::uint64_t seen_ = 0;     // version the worker works on
  bool idle_ = true;
  bool stop_ = false;
  bool cancel_ = false;  // cancel() since the last request
  int allowed_ = -1;     // live stepping: last iteration allowed; -1: all
  bool paused_ = false;
  WorkerProgress progress_;
  std::shared_ptr<const SolveState> latest_;
  std::mutex observer_mutex_;  // held while the observer runs
  Observer observer_;
  std::thread thread_;
};

}  // namespace fetic::app::gui
