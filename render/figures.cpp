// Figures 9.2-9.4 (the thesis problem) and the catalogue that makes every figure by id.

#include "render/figures.hpp"

#include <algorithm>
#include <cmath>

#include "render/colormap.hpp"
#include "render/plot.hpp"
#include "render/scene_drawing.hpp"
#include "render/scene_framing.hpp"
#include "render/text_format.hpp"
#include "render/view.hpp"

namespace fetic::render {
namespace {

Series history_series(const std::vector<solver::HistoryEntry>& history,
                      double solver::HistoryEntry::*field, const std::string& name, Color color) {
  Series series;
  series.name = name;
  series.color = color;
  series.width = 2.2f;
  series.markers = true;
  for (const solver::HistoryEntry& entry : history) {
    series.x.push_back(entry.iteration);
    series.y.push_back(entry.*field);
  }
  return series;
}

void figure_title(DrawList& list, const std::string& title, int width, float text) {
  list.text(title, {0.5f * static_cast<float>(width), 0.5f * text}, text, palette::ink,
            HAlign::Center, VAlign::Top, true);
}

}  // namespace

DrawList figure_solved_scene(const solver::Model& model, const solver::Snapshot& snapshot,
                             const std::string& title, int width, int height) {
  View view;
  view.width = width;
  view.height = height;
  view.show_overlay = false;
  const float text = base_text_size(width, height);
  RunExtent extent;
  const std::vector<solver::HistoryEntry> no_history;
  extent.include(model, Frame{0, 0, snapshot, no_history});
  const Rect region{0.0f, 2.0f * text, static_cast<float>(width),
                    static_cast<float>(height) - 1.6f * text};
  const SceneFraming framing = frame_scene(model, view, extent, region);
  DrawList list;
  figure_title(list, title, width, text);
  list.append(draw_scene(model, snapshot, view, framing));
  const int active = snapshot.active_set_size();
  list.text("red circles: the " + std::to_string(active) + " active contacts of " +
                std::to_string(model.pairs.size()) + "; arrows: loads; colours: subdomains",
            {text, static_cast<float>(height) - 0.5f * text}, 0.9f * text, palette::muted,
            HAlign::Left, VAlign::Bottom);
  return list;
}

DrawList figure_error_and_search_direction(const std::vector<solver::HistoryEntry>& history,
                                           const std::string& method, int width, int height) {
  DrawList list;
  const float text = base_text_size(width, height);
  const auto w = static_cast<float>(width), h = static_cast<float>(height);
  figure_title(list, "Figure 9.3  " + method + " on the thesis problem, per iteration", width,
               text);
  const Axis iterations{"iteration", 0.0,
                        std::max(1.0, history.empty() ? 1.0 : double(history.back().iteration)),
                        false, true};
  PlotSpec error;
  error.frame = {0.0f, 2.0f * text, 0.5f * w, h};
  error.title = "a) error ‖e‖ against the active-set solution";
  error.text_size = text;
  error.x = iterations;
  error.y = {"‖u − u*‖ / ‖u*‖", std::nan(""), std::nan(""), true, false};
  error.series.push_back(
      history_series(history, &solver::HistoryEntry::error, "", series_color(0)));
  list.append(draw_plot(error));
  PlotSpec direction = error;
  direction.frame = {0.5f * w, 2.0f * text, w, h};
  direction.title = "b) size of the search direction ‖w‖";
  direction.y.label = "‖w‖ (relative, the method's residual)";
  direction.series = {
      history_series(history, &solver::HistoryEntry::residual, "", series_color(1))};
  list.append(draw_plot(direction));
  return list;
}

DrawList figure_active_set_sizes(const std::vector<NamedHistory>& runs, int width, int height) {
  DrawList list;
  const float text = base_text_size(width, height);
  figure_title(list, "Figure 9.4  Active constraints per iteration on the thesis problem", width,
               text);
  PlotSpec spec;
  spec.frame = {0.0f, 2.0f * text, static_cast<float>(width), static_cast<float>(height)};
  spec.text_size = text;
  spec.x = {"iteration", 0.0, std::nan(""), false, true};
  spec.y = {"contact pairs in the working set", 0.0, std::nan(""), false, true};
  spec.legend = Corner::BottomRight;
  for (std::size_t r = 0; r < runs.size(); ++r) {
    Series series;
    series.name = runs[r].name + " (" +
                  std::to_string(runs[r].history.empty() ? 0 : runs[r].history.back().iteration) +
                  " iterations)";
    series.color = series_color(static_cast<int>(r));
    series.width = 2.2f;
    series.markers = true;
    series.steps = true;
    for (const solver::HistoryEntry& entry : runs[r].history) {
      series.x.push_back(entry.iteration);
      series.y.push_back(entry.active_set);
    }
    spec.series.push_back(std::move(series));
  }
  list.append(draw_plot(spec));
  return list;
}

const std::vector<FigureInfo>& figure_catalogue() {
  static const std::vector<FigureInfo> catalogue{
      {"2.1", "fig2_1_quadratic_forms.png", "shapes of quadratic forms"},
      {"3.2", "fig3_2_steepest_descent.png", "steepest-descent path on a 2x2 problem"},
      {"4.3", "fig4_3_conjugate_gradients.png", "CG path on the same 2x2 problem"},
      {"9.2", "fig9_2_thesis_solution.png", "the solved thesis problem, active contacts circled"},
      {"9.3", "fig9_3_feti_c_error_and_w.png", "FETI-C error and ||w|| per iteration"},
      {"9.4", "fig9_4_active_set_size.png", "active-set size per iteration, active set vs FETI-C"},
      {"S.1", "figS_1_iterations_by_subdomains.png",
       "iterations against subdomains: active set, FETI-C, MPRGP"},
  };
  return catalogue;
}

struct FigureMaker::Run {
  solver::MethodKind kind;
  std::string problem;  // why the run is missing
  std::vector<solver::HistoryEntry> history;
  solver::Snapshot final;
};

FigureMaker::FigureMaker(const solver::Model* thesis, std::string thesis_problem)
    : thesis_(thesis), thesis_problem_(std::move(thesis_problem)) {}

FigureMaker::~FigureMaker() = default;

const FigureMaker::Run& FigureMaker::run(solver::MethodKind kind) {
  for (const auto& existing : runs_)
    if (existing->kind == kind) return *existing;
  auto result = std::make_unique<Run>();
  result->kind = kind;
  if (!thesis_) {
    result->problem = thesis_problem_;
  } else {
    // The reference for the error of 9.3 is the active-set solution (the thesis used
    // Matlab's quadprog, an active-set QP solver).
    std::vector<std::vector<solver::Vec2>> reference;
    if (kind != solver::MethodKind::ActiveSet) {
      const Run& exact = run(solver::MethodKind::ActiveSet);
      if (exact.problem.empty()) reference = solver::strut_displacements(*thesis_, exact.final);
    }
    try {
      const auto method = solver::make_method(kind, *thesis_, solver::SolveOptions{});
      if (!reference.empty()) method->set_reference(reference);
      method->start(1.0);
      solver::run_to_end(*method);
      result->history = method->history();
      result->final = method->snapshot();
      if (result->final.status != solver::Status::Converged)
        result->problem =
            std::string(solver::to_string(kind)) + " did not converge: " + result->final.message;
    } catch (const solver::SolverError& error) {
      result->problem = std::string(solver::to_string(kind)) + ": " + error.what();
    }
  }
  runs_.push_back(std::move(result));
  return *runs_.back();
}

Figure FigureMaker::make(const std::string& id, int width, int height) {
  Figure figure;
  for (const FigureInfo& info : figure_catalogue())
    if (info.id == id) figure.info = info;
  if (figure.info.id.empty()) {
    figure.note = "no figure " + id;
    return figure;
  }
  if (id == "2.1") {
    figure.drawing = figure_quadratic_forms(width, height);
  } else if (id == "3.2" || id == "4.3") {
    const bool sd = id == "3.2";
    const IteratePath path = gradient_path(sd ? solver::MethodKind::SteepestDescent
                                              : solver::MethodKind::ConjugateGradient);
    figure.drawing = figure_gradient_path(path,
                                          std::string("Figure ") + id + "  " +
                                              (sd ? "Steepest descent" : "Conjugate gradients") +
                                              " on K u = f, 2×2 K (one bar of two elements)",
                                          width, height);
  } else if (id == "9.2") {
    const Run& feti_c = run(solver::MethodKind::FetiC);
    const Run& used = feti_c.problem.empty() ? feti_c : run(solver::MethodKind::ActiveSet);
    if (!used.problem.empty()) {
      figure.note = used.problem;
      return figure;
    }
    if (&used != &feti_c)
      figure.note = "drawn from the active-set solution (" + feti_c.problem + ")";
    figure.drawing = figure_solved_scene(
        *thesis_, used.final,
        std::string("Figure 9.2  The solved thesis problem (") + solver::to_string(used.kind) + ")",
        width, height);
  } else if (id == "9.3") {
    const Run& feti_c = run(solver::MethodKind::FetiC);
    if (!feti_c.problem.empty()) {
      figure.note = feti_c.problem;
      return figure;
    }
    figure.drawing = figure_error_and_search_direction(feti_c.history, "FETI-C", width, height);
  } else if (id == "S.1") {
    // H/h = 4 up to 16x8 subdomains per strut (17,160 unknowns): a few seconds; the
    // benchmark's table 2a runs the same family at H/h = 16.
    constexpr int kElementsPerSubdomain = 4;
    figure.drawing = figure_iterations_by_subdomains(scalability_runs(kElementsPerSubdomain, 16),
                                                     kElementsPerSubdomain, width, height);
  } else if (id == "9.4") {
    const Run& active = run(solver::MethodKind::ActiveSet);
    const Run& feti_c = run(solver::MethodKind::FetiC);
    for (const Run* needed : {&active, &feti_c})
      if (!needed->problem.empty()) {
        figure.note = needed->problem;
        return figure;
      }
    figure.drawing = figure_active_set_sizes(
        {{"active-set method", active.history}, {"FETI-C", feti_c.history}}, width, height);
  }
  return figure;
}

}  // namespace fetic::render
