// The ImGui panel on the left (load slider, method, iteration history, display toggles,
// recordings, status) and the help window. Widgets only push requests; what they show
// is the state the last sync point left.

#include <algorithm>
#include <cmath>
#include <iterator>
#include <string>
#include <utility>

#include <imgui.h>

#include "app/gui/app.hpp"
#include "app/gui/bindings.hpp"
#include "solver/method.hpp"

namespace fetic::app::gui {

void App::panels(float height) {
  ImGui::SetNextWindowPos(ImVec2(0, 0));
  ImGui::SetNextWindowSize(ImVec2(panel_width(), height));
  ImGui::Begin("fetic", nullptr,
               ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse |
                   ImGuiWindowFlags_NoSavedSettings);
  ImGui::TextWrapped("%s", title_.c_str());
  ImGui::Separator();
  load_controls();
  ImGui::Separator();
  solver_controls();
  ImGui::Separator();
  history_controls();
  ImGui::Separator();
  display_toggles();
  ImGui::Separator();
  output_buttons();
  ImGui::Separator();
  status_text();
  ImGui::End();
  if (help_) help_window();
}

// The load factor: slider (reported when taken and let go) and a typed value.
void App::load_controls() {
  ImGui::Text("Load factor (0 .. %.3g)", slider_max_);
  double load = target_.load_factor;
  const double zero = 0.0;
  ImGui::SetNextItemWidth(-1);
  if (ImGui::SliderScalar("##load", ImGuiDataType_Double, &load, &zero, &slider_max_, "%.4f"))
    push({RequestKind::SetLoad, load, {}});
  // Double-click: back to the scene's loads as written (load factor 1).
  if (ImGui::IsItemHovered() && ImGui::IsMouseDoubleClicked(ImGuiMouseButton_Left))
    push({RequestKind::SetLoad, 1.0, {}});
  if (ImGui::IsItemActive() != dragging_slider_) {
    dragging_slider_ = ImGui::IsItemActive();
    log_.write({{"event", "slider"}, {"held", dragging_slider_}, {"load_factor", load}});
  }
  const ImVec2 lo = ImGui::GetItemRectMin(), hi = ImGui::GetItemRectMax();
  slider_[0] = lo.x, slider_[1] = lo.y, slider_[2] = hi.x, slider_[3] = hi.y;
  // The typed value shows the current load factor unless the user is typing.
  if (!typing_load_) typed_load_ = target_.load_factor;
  ImGui::SetNextItemWidth(120);
  if (ImGui::InputDouble("type + Enter", &typed_load_, 0.0, 0.0, "%.4f",
                         ImGuiInputTextFlags_EnterReturnsTrue))
    push({RequestKind::SetLoad, typed_load_, {}});
  typing_load_ = ImGui::IsItemActive();
}

// Method, preconditioner and magnification (automatic or locked).
void App::solver_controls() {
  static const char* methods[] = {"feti-c", "mprgp", "feti-dp", "active-set", "feti", "cg", "sd"};
  constexpr int method_count = static_cast<int>(std::size(methods));
  static const char* preconditioners[] = {"dirichlet", "lumped", "none"};
  int method = 0;
  for (int i = 0; i < method_count; ++i)
    if (solver::to_string(target_.method) == std::string(methods[i])) method = i;
  ImGui::SetNextItemWidth(140);
  if (ImGui::Combo("method", &method, methods, method_count))
    push({RequestKind::SetMethod, 0.0, methods[method]});
  // A second method solving the same scene at the same load, drawn beside the first.
  static const char* compared[] = {"none",       "feti-c", "mprgp", "feti-dp",
                                   "active-set", "feti",   "cg",    "sd"};
  constexpr int compared_count = static_cast<int>(std::size(compared));
  int second = 0;
  for (int i = 1; i < compared_count; ++i)
    if (compare_ && solver::to_string(*compare_) == std::string(compared[i])) second = i;
  ImGui::SetNextItemWidth(140);
  if (ImGui::Combo("compare with", &second, compared, compared_count))
    push({RequestKind::SetCompare, 0.0, compared[second]});
  int pre =
      static_cast<int>(target_.options.preconditioner == solver::Preconditioner::Dirichlet ? 0
                       : target_.options.preconditioner == solver::Preconditioner::Lumped  ? 1
                                                                                           : 2);
  // Only the FETI methods have a preconditioner: the box is greyed out for the others.
  const bool has_preconditioner = solver::is_dual(target_.method);
  ImGui::BeginDisabled(!has_preconditioner);
  ImGui::SetNextItemWidth(140);
  if (ImGui::Combo("preconditioner", &pre, preconditioners, 3))
    push({RequestKind::SetPreconditioner, 0.0, preconditioners[pre]});
  ImGui::EndDisabled();
  bool locked = magnification_ > 0.0;
  if (ImGui::Checkbox("lock magnification", &locked))
    push({RequestKind::SetMagnification, locked ? shown_magnification_ : 0.0, {}});
  ImGui::SameLine();
  if (locked) {
    double m = magnification_;
    ImGui::SetNextItemWidth(90);
    if (ImGui::InputDouble("##mag", &m, 0.0, 0.0, "%.3g", ImGuiInputTextFlags_EnterReturnsTrue) &&
        m > 0.0)
      push({RequestKind::SetMagnification, m, {}});
  } else {
    ImGui::Text("auto: %g", shown_magnification_);
  }
}

// Playback of the iterations of the shown solve.
void App::history_controls() {
  ImGui::Text("Iterations of this solve");
  bool live = live_;
  if (ImGui::Checkbox("step the solver live", &live))
    push({RequestKind::SetLive, live ? 1.0 : 0.0, {}});
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip(
        "On: a new solve stops at iteration 0; Step and Play make the solver itself take\n"
        "the next iteration. Off: every solve runs to the end and Step and Play replay it.");
  if (ImGui::Button(playing_ ? "Pause" : "Play")) push({RequestKind::TogglePlay, 0.0, {}});
  ImGui::SameLine();
  if (ImGui::Button("Step")) push({RequestKind::Step, 0.0, {}});
  ImGui::SameLine();
  if (ImGui::Button("Reset")) push({RequestKind::Reset, 0.0, {}});
  ImGui::SameLine();
  float rate = static_cast<float>(play_rate_);
  ImGui::SetNextItemWidth(-1);
  if (ImGui::SliderFloat("##rate", &rate, 1.0f, 30.0f, "%.0f it/s")) play_rate_ = rate;
  const int last = shown_ ? std::max(0, static_cast<int>(shown_->iterates.size()) - 1) : 0;
  int iteration = shown_index();
  ImGui::SetNextItemWidth(-1);
  if (ImGui::SliderInt("##history", &iteration, 0, last, "iteration %d"))
    push({RequestKind::Scrub, static_cast<double>(iteration), {}});
}

// What the picture shows: the colouring (bending moment only where there are beams), then
// the glyphs and labels.
void App::display_toggles() {
  const render::ColorBy shown = view(1, 1).color_by;
  ImGui::TextUnformatted("colour by:");
  const bool frame = shown_ && shown_->model && shown_->model->frame();
  const std::pair<render::ColorBy, const char*> choices[] = {
      {render::ColorBy::Subdomain, "subdomains"},
      {render::ColorBy::Strut, "struts"},
      {render::ColorBy::Stress, "axial stress"},
      {render::ColorBy::Moment, "bending moment"}};
  for (std::size_t c = 0; c < std::size(choices); ++c) {
    const auto& [color, label] = choices[c];
    if (c % 2 == 1) ImGui::SameLine();
    const bool unavailable = color == render::ColorBy::Moment && !frame && shown != color;
    ImGui::BeginDisabled(unavailable);
    if (ImGui::RadioButton(label, shown == color))
      push({RequestKind::SetColor, 0.0, color_name(color)});
    ImGui::EndDisabled();
    if (unavailable && ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
      ImGui::SetTooltip("Only beams (model = \"frame\") carry a bending moment");
  }
  bool value = forces_;
  if (ImGui::Checkbox("forces", &value)) push({RequestKind::Toggle, 0.0, "forces"});
  ImGui::SameLine();
  value = gaps_;
  if (ImGui::Checkbox("gaps", &value)) push({RequestKind::Toggle, 0.0, "gaps"});
  ImGui::SameLine();
  value = show_overlay_;
  if (ImGui::Checkbox("info", &value)) push({RequestKind::Toggle, 0.0, "overlay"});
  value = labels_;
  if (ImGui::Checkbox("strut labels", &value)) push({RequestKind::Toggle, 0.0, "labels"});
  value = chart_;
  if (ImGui::Checkbox("contact chart", &value)) push({RequestKind::Toggle, 0.0, "chart"});
  value = corners_;
  if (ImGui::Checkbox("FETI-DP corners", &value)) push({RequestKind::Toggle, 0.0, "corners"});
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("Amber discs at the nodes --method feti-dp keeps primal (any method)");
}

// Screenshots, reload and recordings.
void App::output_buttons() {
  if (ImGui::Button("Screenshot (S)")) push({RequestKind::Screenshot, 0.0, {}});
  ImGui::SameLine();
  if (ImGui::Button("Reload (F5)")) push({RequestKind::Reload, 0.0, {}});
  view_buttons();
  if (ImGui::Button("Record iterations")) push({RequestKind::RecordIterations, 0.0, {}});
  if (ImGui::Button("Record load sweep"))
    push({RequestKind::RecordSweep, static_cast<double>(sweep_steps_), {}});
  ImGui::SameLine();
  ImGui::SetNextItemWidth(-1);
  ImGui::SliderInt("##steps", &sweep_steps_, 2, 200, "%d steps");
  if (ImGui::Button("ParaView export")) push({RequestKind::ExportParaView, 0.0, {}});
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("Add the shown iterate to %s/struts.pvd and contacts.pvd",
                      args_.vtu_dir.c_str());
}

// What the solver is doing, or why it cannot: a running solve shows its progress and can
// be cancelled; the state of the shown iterate reads as in the information panel.
void App::status_text() {
  const ImVec4 red(0.8f, 0.1f, 0.1f, 1);
  if (error_ && error_->cancelled) {
    ImGui::TextColored(red, "%s", error_->message.c_str());
    ImGui::TextWrapped("(move the load slider to solve again)");
  } else if (error_) {
    ImGui::TextColored(red, "%s cannot solve this scene:", solver::to_string(error_->method));
    ImGui::TextWrapped("%s", error_->error.c_str());
    ImGui::TextWrapped("(the picture is the last solve; choose another method)");
  }
  const bool working = worker_.busy() && !worker_.paused();
  const WorkerProgress progress = worker_.progress();
  if (working && (progress.surveying || !shown_)) {
    ImGui::Text("fixing the scales: solving at load %.4g", slider_max_);
    ImGui::Text("iteration %d, residual %.2e", progress.iteration, progress.residual);
  }
  if (shown_ && !error_) {
    const int last = last_index();
    const solver::Snapshot* newest =
        shown_->iterates.empty() ? nullptr : shown_->iterates.back().get();
    ImGui::Text("load %.4f: %s", shown_->load_factor, shown_status().c_str());
    if (shown_->cancelled) ImGui::TextColored(red, "%s", shown_->message.c_str());
    ImGui::Text("%d iterations, %.2f ms", last, shown_->solve_seconds * 1e3);
    ImGui::Text("residual %.3e, active contacts %d of %d", newest ? newest->residual : 0.0,
                newest ? newest->active_set_size() : 0,
                static_cast<int>(shown_->model->pairs.size()));
    if (!shown_->message.empty() && shown_->status == solver::Status::Failed)
      ImGui::TextColored(red, "%s", shown_->message.c_str());
  } else if (!shown_ && !working) {
    ImGui::Text("setting up the solver ...");
  }
  if (working) {
    // Progress of a solve: the residual's way down from iteration 0 to the tolerance, on a
    // log scale (iterations to go are not known in advance).
    double fraction = 0.0;
    if (shown_ && !shown_->history.empty() && !progress.surveying) {
      const double first = shown_->history.front().residual;
      const double tolerance = target_.options.tolerance;
      if (first > tolerance && progress.residual > 0.0)
        fraction = std::log(first / progress.residual) / std::log(first / tolerance);
    }
    ImGui::ProgressBar(static_cast<float>(std::clamp(fraction, 0.0, 1.0)), ImVec2(-90, 0),
                       progress.surveying ? "scales" : "residual");
    ImGui::SameLine();
    if (ImGui::Button("Cancel (C)")) push({RequestKind::Cancel, 0.0, {}});
  }
  if (!status_line_.empty()) {
    if (status_is_error_) ImGui::PushStyleColor(ImGuiCol_Text, red);
    ImGui::TextWrapped("%s", status_line_.c_str());
    if (status_is_error_) ImGui::PopStyleColor();
  }
  ImGui::TextDisabled("H: keys   drag: pan   wheel: zoom");
}

void App::help_window() {
  ImGui::SetNextWindowPos(ImVec2(panel_width() + 40, 40));
  ImGui::Begin("Keys", &help_,
               ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoSavedSettings);
  if (ImGui::BeginTable("keys", 2)) {
    for (const auto& [keys, does] : help_rows()) {  // the table the key handler uses
      ImGui::TableNextRow();
      ImGui::TableSetColumnIndex(0);
      ImGui::TextUnformatted(keys.c_str());
      ImGui::TableSetColumnIndex(1);
      ImGui::TextUnformatted(does.c_str());
    }
    ImGui::EndTable();
  }
  ImGui::End();
}

}  // namespace fetic::app::gui
