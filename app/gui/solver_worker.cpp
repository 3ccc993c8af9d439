#include "app/gui/solver_worker.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "app/gui/iterate_store.hpp"
#include "app/render_output.hpp"
#include "solver/interruption.hpp"
#include "solver/load_sweep.hpp"

namespace fetic::app::gui {

namespace {

// From this many unknowns a solve takes long enough that the window's first solve at load
// 1 (which chooses the slider's top) is kept as the warm start of the next one. Smaller
// scenes solve cold after the survey, whatever the first load (the tests count those
// iterations).
constexpr long long kLargeScene = 500000;

}  // namespace

double automatic_max_load(const solver::Model& model, const solver::Snapshot& at_one) {
  if (at_one.status != solver::Status::Converged || at_one.active_set_size() > 0) return 2.0;
  const auto u = solver::strut_displacements(model, at_one);
  double first_close = std::numeric_limits<double>::infinity();
  for (const solver::ContactPair& pair : model.pairs) {
    const solver::Vec2 relative =
        u[static_cast<std::size_t>(pair.strut_a)][static_cast<std::size_t>(pair.node_a)] -
        u[static_cast<std::size_t>(pair.strut_b)][static_cast<std::size_t>(pair.node_b)];
    const double closing = relative.dot(pair.normal);  // row: (u_a - u_b) . n <= gap
    if (closing > 0.0 && pair.gap > 0.0) first_close = std::min(first_close, pair.gap / closing);
  }
  if (!std::isfinite(first_close) || 2.0 * first_close <= 2.0) return 2.0;
  const double raw = 2.0 * first_close;
  const double decade = std::pow(10.0, std::floor(std::log10(raw)));
  for (const double step : {1.0, 2.0, 5.0, 10.0})
    if (step * decade >= raw) return step * decade;
  return 10.0 * decade;
}

SolverWorker::SolverWorker(std::function<void()> wake) : wake_(std::move(wake)) {
  thread_ = std::thread([this] { run(); });
}

SolverWorker::~SolverWorker() {
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  changed_.notify_all();
  thread_.join();
}

void SolverWorker::request(const SolverTarget& target) {
  {
    std::lock_guard lock(mutex_);
    target_ = target;
    ++version_;
    idle_ = false;
    cancel_ = false;
    allowed_ = target.live ? 0 : -1;
  }
  changed_.notify_all();
}

void SolverWorker::cancel() {
  {
    std::lock_guard lock(mutex_);
    if (idle_) return;
    cancel_ = true;
  }
  changed_.notify_all();
}

void SolverWorker::allow(int iterations) {
  {
    std::lock_guard lock(mutex_);
    allowed_ = iterations;
  }
  changed_.notify_all();
}

void SolverWorker::observe_with(Observer observer) {
  std::lock_guard lock(observer_mutex_);
  observer_ = std::move(observer);
}

void SolverWorker::notify_observer(const solver::Model& model, const solver::Method& method,
                                   double load_factor, bool started) {
  std::lock_guard lock(observer_mutex_);
  if (observer_) observer_(model, method, load_factor, started);
}

bool SolverWorker::paused() const {
  std::lock_guard lock(mutex_);
  return paused_;
}

WorkerProgress SolverWorker::progress() const {
  std::lock_guard lock(mutex_);
  WorkerProgress progress = progress_;
  progress.paused = paused_;
  return progress;
}

void SolverWorker::set_progress(const WorkerProgress& progress) {
  std::lock_guard lock(mutex_);
  progress_ = progress;
}

bool SolverWorker::cancel_requested() const {
  std::lock_guard lock(mutex_);
  return cancel_;
}

bool SolverWorker::wait_for_allowance(int iteration) {
  std::unique_lock lock(mutex_);
  const auto free = [&] {
    return stop_ || version_ != seen_ || cancel_ || allowed_ < 0 || iteration < allowed_;
  };
  if (!free()) {
    paused_ = true;
    lock.unlock();
    if (wake_) wake_();  // the UI may stop polling while the solver waits
    lock.lock();
    changed_.wait(lock, free);
    paused_ = false;
  }
  return !(stop_ || version_ != seen_ || cancel_);
}

std::shared_ptr<const SolveState> SolverWorker::latest() const {
  std::lock_guard lock(mutex_);
  return latest_;
}

bool SolverWorker::busy() const {
  std::lock_guard lock(mutex_);
  return !idle_;
}

bool SolverWorker::superseded() const {
  std::lock_guard lock(mutex_);
  return stop_ || version_ != seen_;
}

std::shared_ptr<const SolveState> SolverWorker::wait_for(std::uint64_t request,
                                                         std::chrono::microseconds budget) const {
  std::unique_lock lock(mutex_);
  published_.wait_for(lock, budget,
                      [&] { return latest_ && latest_->request >= request && latest_->finished; });
  return latest_;
}

void SolverWorker::publish(std::shared_ptr<const SolveState> state) {
  {
    std::lock_guard lock(mutex_);
    // A finished answer to the newest request makes the worker idle in the same step, so
    // that whoever sees it also sees busy() false.
    if (state->finished && version_ == seen_ && state->request == target_.request) idle_ = true;
    latest_ = std::move(state);
  }
  published_.notify_all();
  if (wake_) wake_();
}

void SolverWorker::publish_cancelled_survey(const SolverTarget& target) {
  auto state = std::make_shared<SolveState>();
  state->model = target.model;
  state->model_generation = target.model_generation;
  state->request = target.request;
  state->load_factor = target.load_factor;
  state->method = target.method;
  state->preconditioner = target.options.preconditioner;
  state->finished = true;
  state->cancelled = true;
  state->message = "cancelled while solving at the top of the slider for the picture's scales";
  publish(state);
  mark_idle();
}

void SolverWorker::mark_idle() {
  std::lock_guard lock(mutex_);
  if (version_ == seen_) idle_ = true;
}

// The worker's loop: wait for a request, set the method up (when the model or the method
// changed), survey the slider's top for the picture's scales (when the range changed),
// then solve at the requested load factor.
void SolverWorker::run() {
  Setup setup;
  for (;;) {
    SolverTarget target;
    if (!next_target(target)) return;
    if (!target.model) continue;
    const bool remake = needs_remake(setup, target);
    if (remake) make_method(setup, target);
    if (remake || setup.max_load != target.max_load)
      if (!survey_scales(setup, target)) continue;
    solve(setup, target);
  }
}

bool SolverWorker::next_target(SolverTarget& target) {
  std::unique_lock lock(mutex_);
  changed_.wait(lock, [&] { return stop_ || version_ != seen_; });
  if (stop_) return false;
  seen_ = version_;
  target = target_;
  return true;
}

bool SolverWorker::needs_remake(const Setup& setup, const SolverTarget& target) {
  if (!setup.method && setup.error.empty()) return true;
  return setup.generation != target.model_generation || setup.kind != target.method ||
         setup.options.preconditioner != target.options.preconditioner ||
         setup.options.scaling != target.options.scaling ||
         setup.options.tolerance != target.options.tolerance ||
         setup.options.max_iterations != target.options.max_iterations;
}

void SolverWorker::make_method(Setup& setup, const SolverTarget& target) {
  setup.driver.reset();
  setup.method.reset();
  setup.error.clear();
  // Small models solve fastest on one thread: an OpenMP team's start-up and spinning
  // cost more than the work and take the cores the window renders on (llvmpipe).
  use_solver_threads_for_pictures(*target.model);
  try {
    setup.model = target.model;
    setup.method = solver::make_method(target.method, *setup.model, target.options);
    setup.driver = std::make_unique<solver::SweepDriver>(*setup.method);
  } catch (const solver::SolverError& error) {
    setup.error = error.what();
  } catch (const solver::SetupInterrupted& stop) {  // the program is being ended
    setup.method.reset();
    setup.error = std::string("interrupted while ") + stop.during();
  }
  setup.generation = target.model_generation;
  setup.kind = target.method;
  setup.options = target.options;
  setup.max_load = -1.0;
}

// Fixed scales for the slider range: every iteration of the solve at its top (cold, so
// that the scales do not depend on the order of the requests). False when superseded or
// cancelled meanwhile.
bool SolverWorker::survey_scales(Setup& setup, const SolverTarget& target) {
  setup.max_load = target.max_load;
  setup.slider_max = target.max_load > 0.0 ? target.max_load : 2.0;
  auto survey = std::make_shared<render::RunExtent>();
  solver::Method* method = setup.method.get();
  const auto keep_surveying = [&] {
    WorkerProgress progress;
    progress.surveying = true;
    progress.iteration = method->iteration();
    if (!method->history().empty()) {
      progress.residual = method->history().back().residual;
      progress.active_set = method->history().back().active_set;
    }
    set_progress(progress);
    return !superseded() && !cancel_requested();
  };
  const auto stopped = [&] {
    if (keep_surveying()) return false;
    setup.max_load = -1.0;  // survey again with the next request
    if (cancel_requested()) publish_cancelled_survey(target);
    return true;
  };
  if (method && target.max_load <= 0.0) {
    if (target.model->dof_count() >= kLargeScene) {
      // Through the driver, so that the solve at load 1 that follows the survey starts
      // from this one (converged at once) instead of solving it a third time.
      solver::SweepHooks hooks;
      hooks.keep_going = keep_surveying;
      setup.driver->solve(1.0, hooks);
    } else {
      method->start(1.0);
      solver::run_to_end(*method, keep_surveying);
    }
    if (stopped()) return false;
    setup.slider_max = automatic_max_load(*target.model, method->snapshot());
  }
  if (method) {
    render::FramePlan plan;
    plan.load_factors = {setup.slider_max};
    *survey = render::survey(*target.model, *method, plan, keep_surveying);
    if (stopped()) return false;
  }
  setup.extent = survey;
  return true;
}

// The solve at the requested load factor through the sweep driver (the warm starts of
// `fetic solve --load-steps`), publishing every iterate; a newer request or cancel()
// stops it between two iterations, and the next solve starts from where it got to.
void SolverWorker::solve(Setup& setup, SolverTarget target) {
  using Clock = std::chrono::steady_clock;
  auto state = std::make_shared<SolveState>();
  state->model = target.model;
  state->model_generation = target.model_generation;
  state->request = target.request;
  state->method = target.method;
  state->preconditioner = target.options.preconditioner;
  state->extent = setup.extent;
  state->max_load = setup.slider_max;
  target.load_factor = std::min(target.load_factor, setup.slider_max);
  state->load_factor = target.load_factor;
  if (!setup.method) {
    state->finished = true;
    state->status = solver::Status::Failed;
    state->error = setup.error;
    state->message = setup.error;
    publish(state);
    mark_idle();
    return;
  }
  const auto begin = Clock::now();
  bool abandoned = false;
  std::size_t keep = 0;  // distinct iterates kept (iterate_store.hpp)
  solver::SweepHooks hooks;
  hooks.keep_going = [&] {
    abandoned = !wait_for_allowance(setup.method->iteration()) || superseded();
    return !abandoned;
  };
  hooks.on_iteration = [&](double t, const solver::Method& method) {
    auto snapshot = std::make_shared<const solver::Snapshot>(method.snapshot());
    if (keep == 0) keep = iterates_within(*snapshot, kIterateBudget);
    append_iterate(state->iterates, std::move(snapshot), keep);
    state->history = method.history();
    state->status = method.status();
    state->message = method.message();
    state->solve_seconds = std::chrono::duration<double>(Clock::now() - begin).count();
    state->finished = method.status() != solver::Status::Running;
    if (state->finished) state->finished_at = Clock::now();
    WorkerProgress progress;
    progress.iteration = method.iteration();
    if (!state->history.empty()) {
      progress.residual = state->history.back().residual;
      progress.active_set = state->history.back().active_set;
    }
    set_progress(progress);
    notify_observer(*target.model, method, t, state->iterates.size() == 1);
    publish(std::make_shared<const SolveState>(*state));
  };
  setup.driver->solve(target.load_factor, hooks);
  if (!abandoned) {
    mark_idle();  // the last publication was finished
  } else if (cancel_requested() && !superseded()) {
    state->finished = true;
    state->finished_at = Clock::now();
    state->cancelled = true;
    state->message = "cancelled at iteration " + std::to_string(setup.method->iteration());
    publish(std::make_shared<const SolveState>(*state));
    mark_idle();
  }
}

}  // namespace fetic::app::gui
