#include "app/gui/solver_worker.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "app/render_output.hpp"
#include "solver/load_sweep.hpp"

namespace fetic::app::gui {

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
  std::lock_guard lock(mutex_);
  if (version_ == seen_) idle_ = true;
}

void SolverWorker::run() {
  using Clock = std::chrono::steady_clock;
  std::unique_ptr<solver::Method> method;
  // What the current method was made for.
  std::shared_ptr<const solver::Model> made_model;  // keeps the method's model alive
  std::uint64_t made_generation = 0;
  solver::MethodKind made_kind{};
  solver::SolveOptions made_options;
  double made_max_load = -1.0;
  std::shared_ptr<const render::RunExtent> extent;
  double slider_max = 2.0;
  std::string setup_error;
  // The last two finished solves (secant warm start), or an abandoned iterate.
  std::unique_ptr<solver::Snapshot> older, newer;

  for (;;) {
    SolverTarget target;
    {
      std::unique_lock lock(mutex_);
      changed_.wait(lock, [&] { return stop_ || version_ != seen_; });
      if (stop_) return;
      seen_ = version_;
      target = target_;
    }
    if (!target.model) continue;

    const bool remake = !method && setup_error.empty()
                            ? true
                            : made_generation != target.model_generation ||
                                  made_kind != target.method ||
                                  made_options.preconditioner != target.options.preconditioner ||
                                  made_options.scaling != target.options.scaling ||
                                  made_options.tolerance != target.options.tolerance ||
                                  made_options.max_iterations != target.options.max_iterations;
    if (remake || made_max_load != target.max_load) {
      if (remake) {
        method.reset();
        setup_error.clear();
        older.reset();
        newer.reset();
        // Small models solve fastest on one thread: an OpenMP team's start-up and spinning
        // cost more than the work and take the cores the window renders on (llvmpipe).
        use_solver_threads_for_pictures(*target.model);
        try {
          made_model = target.model;
          method = solver::make_method(target.method, *made_model, target.options);
        } catch (const solver::SolverError& error) {
          setup_error = error.what();
        }
        made_generation = target.model_generation;
        made_kind = target.method;
        made_options = target.options;
      }
      // Fixed scales for the slider range: every iteration of the solve at its top.
      made_max_load = target.max_load;
      slider_max = target.max_load > 0.0 ? target.max_load : 2.0;
      auto survey = std::make_shared<render::RunExtent>();
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
      if (method && target.max_load <= 0.0) {
        method->start(1.0);
        solver::run_to_end(*method, keep_surveying);
        if (!keep_surveying()) {
          made_max_load = -1.0;
          if (cancel_requested()) publish_cancelled_survey(target);
          continue;
        }
        slider_max = automatic_max_load(*target.model, method->snapshot());
      }
      if (method) {
        render::FramePlan plan;
        plan.load_factors = {slider_max};
        *survey = render::survey(*target.model, *method, plan, keep_surveying);
        if (!keep_surveying()) {
          made_max_load = -1.0;  // survey again with the next request
          if (cancel_requested()) publish_cancelled_survey(target);
          continue;
        }
      }
      extent = survey;
    }

    auto state = std::make_shared<SolveState>();
    state->model = target.model;
    state->model_generation = target.model_generation;
    state->request = target.request;
    state->load_factor = target.load_factor;
    state->method = target.method;
    state->preconditioner = target.options.preconditioner;
    state->extent = extent;
    state->max_load = slider_max;
    target.load_factor = std::min(target.load_factor, slider_max);
    state->load_factor = target.load_factor;
    if (!method) {
      state->finished = true;
      state->status = solver::Status::Failed;
      state->error = setup_error;
      state->message = setup_error;
      publish(state);
      std::lock_guard lock(mutex_);
      if (version_ == seen_) idle_ = true;
      continue;
    }

    const auto begin = Clock::now();
    if (newer) {
      const solver::Snapshot warm =
          solver::predict_warm_start(older.get(), *newer, target.load_factor);
      method->start(target.load_factor, &warm);
    } else {
      method->start(target.load_factor);
    }
    const auto take = [&] {
      state->iterates.push_back(std::make_shared<const solver::Snapshot>(method->snapshot()));
      state->history = method->history();
      state->status = method->status();
      state->message = method->message();
      state->solve_seconds = std::chrono::duration<double>(Clock::now() - begin).count();
      WorkerProgress progress;
      progress.iteration = method->iteration();
      if (!state->history.empty()) {
        progress.residual = state->history.back().residual;
        progress.active_set = state->history.back().active_set;
      }
      set_progress(progress);
    };
    take();
    notify_observer(*target.model, *method, target.load_factor, true);
    publish(std::make_shared<const SolveState>(*state));
    bool abandoned = false;
    while (method->status() == solver::Status::Running) {
      if (!wait_for_allowance(method->iteration()) || superseded()) {
        abandoned = true;
        break;
      }
      method->step();
      take();
      notify_observer(*target.model, *method, target.load_factor, false);
      state->finished = method->status() != solver::Status::Running;
      publish(std::make_shared<const SolveState>(*state));
    }
    if (abandoned && cancel_requested() && !superseded()) {
      state->finished = true;
      state->cancelled = true;
      state->message = "cancelled at iteration " + std::to_string(method->iteration());
      publish(std::make_shared<const SolveState>(*state));
      newer = std::make_unique<solver::Snapshot>(*state->iterates.back());
      older.reset();
      std::lock_guard lock(mutex_);
      if (version_ == seen_) idle_ = true;
      continue;
    }
    if (abandoned) {
      // The next solve starts from where this one got to (no secant: not a solution).
      newer = std::make_unique<solver::Snapshot>(*state->iterates.back());
      older.reset();
      continue;
    }
    state->finished = true;
    if (state->iterates.size() == 1) publish(std::make_shared<const SolveState>(*state));
    if (method->status() == solver::Status::Converged) {
      older = std::move(newer);
      newer = std::make_unique<solver::Snapshot>(*state->iterates.back());
    }
    std::lock_guard lock(mutex_);
    if (version_ == seen_) idle_ = true;
  }
}

}  // namespace fetic::app::gui
