// After each swap: what is on screen now, for the state file ("solved" events) and the
// script's "wait"; the benchmark's latencies are taken here too.

#include <chrono>
#include <iterator>
#include <vector>

#include "app/gui/app.hpp"
#include "solver/method.hpp"

namespace fetic::app::gui {
namespace {

std::vector<int> active_contacts(const solver::Snapshot& snapshot) {
  std::vector<int> active;
  for (std::size_t i = 0; i < snapshot.in_working_set.size(); ++i)
    if (snapshot.in_working_set[i]) active.push_back(static_cast<int>(i));
  return active;
}

}  // namespace

void App::report_frame() {
  // Called after a swap: the shown state is on screen now.
  if (error_ && error_->request > reported_request_) {
    reported_request_ = error_->request;
    log_.write({{"event", "solved"},
                {"request", error_->request},
                {"load_factor", error_->load_factor},
                {"method", solver::to_string(error_->method)},
                {"converged", false},
                {"status", "failed"},
                {"message", error_->message},
                {"active", 0},
                {"active_contacts", std::vector<int>{}}});
  }
  if (!shown_) {
    solved_on_screen_ = error_ && error_->request == requests_sent_;
    return;
  }
  const auto now = Clock::now();
  if (shown_->request != first_frame_request_) {
    first_frame_request_ = shown_->request;
    if (const auto it = requested_at_.find(shown_->request);
        it != requested_at_.end() && args_.bench > 0 && bench_.phase == 2)
      bench_.first_latency_ms.push_back(
          std::chrono::duration<double, std::milli>(now - it->second).count());
  }
  // Comparing, a solve counts as on screen once the second method has answered it too.
  const bool second_done = !compare_ || (compare_shown_ && compare_shown_->finished &&
                                         compare_shown_->request >= shown_->request);
  solved_on_screen_ = (shown_->finished && second_done && shown_->request == requests_sent_ &&
                       (follow_ || !playing_)) ||
                      (error_ && error_->request == requests_sent_);
  if (!shown_->finished || !second_done || shown_->request <= reported_request_ ||
      shown_->iterates.empty())
    return;
  reported_request_ = shown_->request;
  const solver::Snapshot& final_state = *shown_->iterates.back();
  double latency = 0.0;
  if (const auto it = requested_at_.find(shown_->request); it != requested_at_.end()) {
    latency = std::chrono::duration<double, std::milli>(now - it->second).count();
    requested_at_.erase(requested_at_.begin(), std::next(it));
  }
  if (args_.bench > 0 && bench_.phase == 2 && shown_->request == bench_.waiting) {
    bench_.solved_latency_ms.push_back(latency);
    bench_.solve_ms.push_back(shown_->solve_seconds * 1e3);
    bench_.iterations.push_back(static_cast<int>(shown_->iterates.size()) - 1);
  }
  const std::vector<int> active = active_contacts(final_state);
  nlohmann::json second;
  if (compare_ && compare_shown_ && !compare_shown_->iterates.empty()) {
    const auto& history = compare_shown_->history;
    second = {{"method", solver::to_string(compare_shown_->method)},
              {"iterations", static_cast<int>(compare_shown_->iterates.size()) - 1},
              {"f_applications", history.empty() ? -1LL : history.back().f_applications},
              {"converged", compare_shown_->status == solver::Status::Converged},
              {"active_contacts", active_contacts(*compare_shown_->iterates.back())}};
  }
  log_.write(
      {{"event", "solved"},
       {"request", shown_->request},
       {"load_factor", shown_->load_factor},
       {"method", solver::to_string(shown_->method)},
       {"preconditioner", solver::to_string(shown_->preconditioner)},
       {"iterations", static_cast<int>(shown_->iterates.size()) - 1},
       {"f_applications", shown_->history.empty() ? -1LL : shown_->history.back().f_applications},
       {"converged", shown_->status == solver::Status::Converged},
       {"status", shown_->cancelled ? "cancelled" : solver::to_string(shown_->status)},
       {"cancelled", shown_->cancelled},
       {"message", shown_->message},
       {"active", static_cast<int>(active.size())},
       {"active_contacts", active},
       {"solve_ms", shown_->solve_seconds * 1e3},
       {"latency_ms", latency},
       // From the solve's end to the frame that shows it (the picture of a huge scene).
       {"shown_after_solve_ms",
        std::chrono::duration<double, std::milli>(now - shown_->finished_at).count()},
       {"compare", second}});
}

}  // namespace fetic::app::gui
