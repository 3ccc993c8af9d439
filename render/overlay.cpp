#include "render/overlay.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "render/colormap.hpp"
#include "render/plot.hpp"
#include "render/text_format.hpp"
#include "scenes/units.hpp"

namespace fetic::render {

Rect overlay_panel(const View& view) {
  const auto width = static_cast<float>(view.width), height = static_cast<float>(view.height);
  // 28% of the width, up to 24 text heights (360 pixels at 1280x720), so that it grows
  // with the text on large frames.
  const float text = text_size(view);
  const float panel = std::max(150.0f, std::min(0.28f * width, 24.0f * text));
  const float margin = std::max(4.0f, 0.5f * text_size(view));
  return {width - panel - margin, margin, width - margin, height - margin};
}

Rect chart_region(const View& view) {
  if (!view.show_chart) return {};
  const auto width = static_cast<float>(view.width), height = static_cast<float>(view.height);
  const float right = view.show_overlay ? overlay_panel(view).x0 : width;
  const float text = text_size(view);
  const float margin = std::max(4.0f, 0.5f * text);
  // 40% of what the panel leaves, at least 20 text heights (the axes need them).
  const float chart = std::min(0.6f * right, std::max(0.4f * right, 20.0f * text));
  return {right - chart, margin, right - margin, height - margin};
}

Rect scene_region(const View& view) {
  const auto width = static_cast<float>(view.width), height = static_cast<float>(view.height);
  const float right = view.show_chart     ? chart_region(view).x0
                      : view.show_overlay ? overlay_panel(view).x0
                                          : width;
  return {0.0f, 0.0f, right, height};
}

namespace {

// A range that holds [fixed_low, fixed_high] and every finite value in `data`.
std::pair<double, double> holding(double fixed_low, double fixed_high,
                                  const std::vector<double>& data, bool positive_only) {
  double low = fixed_low, high = fixed_high;
  for (double v : data)
    if (std::isfinite(v) && (!positive_only || v > 0.0)) {
      low = std::min(low, v);
      high = std::max(high, v);
    }
  return {low, high};
}

// The residual plot (log scale) of one solve's iterations.
PlotArea residual_plot(DrawList& list, const Rect& frame, float t, const Axis& x_axis,
                       const std::vector<double>& iterations, const std::vector<double>& residuals,
                       const RunExtent& extent) {
  PlotSpec plot;
  plot.frame = frame;
  plot.title = "relative residual";
  plot.text_size = 0.85f * t;
  plot.x = x_axis;
  plot.x.label.clear();
  plot.y.log = true;
  const double inf = std::numeric_limits<double>::infinity();
  const auto [low, high] =
      holding(extent.smallest_residual > 0.0 ? extent.smallest_residual : inf,
              extent.largest_residual > 0.0 ? extent.largest_residual : -inf, residuals, true);
  if (std::isfinite(low) && std::isfinite(high)) {
    plot.y.min = std::pow(10.0, std::floor(std::log10(low) + 1e-9));
    plot.y.max = std::pow(10.0, std::ceil(std::log10(high) - 1e-9));
    if (plot.y.max <= plot.y.min) plot.y.max = 10.0 * plot.y.min;
  }
  const float u = std::max(1.0f, plot.text_size / 12.0f);
  plot.series.push_back({"", iterations, residuals, series_color(0), 1.8f * u, false, false});
  const PlotArea area = draw_axes(list, plot);
  draw_series(list, area, plot.series.front());
  // An exact zero cannot sit on a log axis: at the floor, as a hollow mark labelled 0.
  bool zero_labelled = false;
  for (std::size_t i = 0; i < residuals.size(); ++i)
    if (residuals[i] == 0.0) {
      const Point p = area.to_pixel(iterations[i], area.y_min());
      list.ring(p, 3.0f * u, 1.4f * u, series_color(0));
      if (!zero_labelled) {
        list.text("0", {p.x + 4.0f * u, p.y - 2.0f * u}, 0.8f * plot.text_size, series_color(0),
                  HAlign::Left, VAlign::Bottom);
        zero_labelled = true;
      }
    }
  if (!residuals.empty() && residuals.back() > 0.0) {
    const Point current = area.to_pixel(iterations.back(), residuals.back());
    if (area.inner().contains(current)) list.disc(current, 3.0f * u, series_color(0));
  }
  return area;
}

// A count (or amount) against a shared x axis, with the newest point marked.
PlotArea value_plot(DrawList& list, const Rect& frame, float t, const std::string& title,
                    const Axis& x_axis, const std::vector<double>& x, const std::vector<double>& y,
                    double fixed_high, Color color, bool steps, bool integer) {
  PlotSpec plot;
  plot.frame = frame;
  plot.title = title;
  plot.text_size = 0.85f * t;
  plot.x = x_axis;
  const auto [low, high] = holding(0.0, fixed_high, y, false);
  plot.y = {"", std::min(0.0, low), std::max(integer ? 1.0 : high, high), false, integer};
  if (!(plot.y.max > plot.y.min)) plot.y.max = plot.y.min + 1.0;
  const float u = std::max(1.0f, plot.text_size / 12.0f);
  plot.series.push_back({"", x, y, color, 1.8f * u, !steps, steps});
  const PlotArea area = draw_axes(list, plot);
  draw_series(list, area, plot.series.front());
  if (!x.empty()) list.disc(area.to_pixel(x.back(), y.back()), 3.0f * u, color);
  return area;
}

// The title and the rows of the panel (method, load factor, iteration, ...); returns the
// height where the plots below them start.
float draw_overlay_rows(DrawList& list, const OverlayInfo& info, const solver::Model& model,
                        const solver::Snapshot& snapshot, const View& view, const Rect& panel) {
  const float t = text_size(view);
  const float pad = 0.6f * t;
  float y = panel.y0 + pad;
  const float x0 = panel.x0 + pad, x1 = panel.x1 - pad;
  const float title_size = std::round(1.1f * t);
  for (const std::string& line :
       wrap(info.title.empty() ? "(untitled scene)" : info.title, x1 - x0, title_size, true)) {
    list.text(line, {x0, y}, title_size, palette::ink, HAlign::Left, VAlign::Top, true);
    y += 1.25f * title_size;
  }
  y += 0.3f * t;

  const float row_size = 0.95f * t;
  const float key_width = estimated_text_width("load factor", row_size) + 0.6f * t;
  const auto row = [&](const std::string& key, const std::string& value, Color color) {
    list.text(key, {x0, y}, row_size, palette::muted);
    // A value too long for the panel is set smaller rather than spill over its edge.
    const float room = x1 - x0 - key_width;
    const float width = estimated_text_width(value, row_size);
    const float size = width > room ? std::max(0.7f * row_size, row_size * room / width) : row_size;
    list.text(value, {x0 + key_width, y + 0.5f * (row_size - size)}, size, color);
    y += 1.3f * row_size;
  };
  row("method", info.method, palette::ink);
  row("load factor",
      format("%.4g", snapshot.load_factor) +
          (info.load_step.empty() ? "" : "  (" + info.load_step + ")"),
      palette::ink);
  row("iteration", std::to_string(snapshot.iteration), palette::ink);
  row("residual", format("%.3e", snapshot.residual), palette::ink);
  if (!model.pairs.empty())
    row("active set",
        std::to_string(snapshot.active_set_size()) + " of " + std::to_string(model.pairs.size()),
        palette::ink);  // not red: red is for a failed status, and 0 of 1 is no error
  const Color status_color = snapshot.status == solver::Status::Failed      ? palette::contact
                             : snapshot.status == solver::Status::Converged ? Color{0, 130, 70, 255}
                                                                            : palette::ink;
  row("status", info.status.empty() ? solver::to_string(snapshot.status) : info.status,
      status_color);
  row("colour",
      view.color_by == ColorBy::Stress   ? "axial stress"
      : view.color_by == ColorBy::Moment ? "bending moment"
      : view.color_by == ColorBy::Strut  ? "struts"
                                         : "subdomains",
      palette::ink);
  return y + 0.4f * t;
}

// Against the load factor: iterations per step, the active set, the total contact force -
// one point per step, fixed to the whole run so that frames line up.
void draw_step_plots(DrawList& list, const Rect& region, float t, const solver::Model& model,
                     const StepSeries& steps, std::vector<PlotArea>& plots) {
  std::vector<double> loads, iterations, active, force;
  for (const StepSummary& step : steps.shown) {
    loads.push_back(step.load_factor);
    iterations.push_back(step.iterations);
    active.push_back(step.active_set);
    force.push_back(step.total_force);
  }
  double first = steps.all.front().load_factor, last = first;
  int most_iterations = 1, most_active = 1;
  double most_force = 0.0;
  for (const StepSummary& step : steps.all) {
    first = std::min(first, step.load_factor);
    last = std::max(last, step.load_factor);
    most_iterations = std::max(most_iterations, step.iterations);
    most_active = std::max(most_active, step.active_set);
    most_force = std::max(most_force, step.total_force);
  }
  if (!(last > first)) last = first + 1.0;
  const Axis x_axis{"load factor", first, last, false, false};
  const bool with_contacts = !model.pairs.empty();
  const float left = region.x0, right = region.x1, y = region.y0, bottom = region.y1;
  const float height = (bottom - y) / (with_contacts ? 3.0f : 1.0f);
  plots.push_back(value_plot(list, {left, y, right, y + height}, t, "iterations per step", x_axis,
                             loads, iterations, most_iterations, series_color(0), false, true));
  if (!with_contacts) return;
  plots.push_back(value_plot(list, {left, y + height, right, y + 2 * height}, t,
                             "active set (contact pairs)", x_axis, loads, active, most_active,
                             palette::contact, false, true));
  const scenes::DisplayUnit unit =
      scenes::display_unit(scenes::Quantity::Force, model.units, most_force);
  std::vector<double> shown_force;
  for (double f : force)
    shown_force.push_back(f / unit.divisor);
  plots.push_back(value_plot(list, {left, y + 2 * height, right, bottom}, t,
                             "total contact force [" + unit.name + "]", x_axis, loads, shown_force,
                             most_force / unit.divisor, palette::force, false, false));
}

// Against the iterations of this solve, fixed to the whole run so that frames line up (and
// widened where this solve goes beyond it).
void draw_iteration_plots(DrawList& list, const Rect& region, float t, bool with_contacts,
                          const std::vector<solver::HistoryEntry>& history, const RunExtent& extent,
                          std::vector<PlotArea>& plots) {
  std::vector<double> iterations, residuals, active;
  for (const solver::HistoryEntry& entry : history) {
    iterations.push_back(entry.iteration);
    residuals.push_back(entry.residual);
    active.push_back(entry.active_set);
  }
  const double last_iteration = std::max({1.0, static_cast<double>(extent.largest_iteration),
                                          iterations.empty() ? 0.0 : iterations.back()});
  const Axis x_axis{"iteration", 0.0, last_iteration, false, true};
  const float left = region.x0, right = region.x1, y = region.y0, bottom = region.y1;
  const float height = with_contacts ? 0.5f * (bottom - y) : bottom - y;
  plots.push_back(
      residual_plot(list, {left, y, right, y + height}, t, x_axis, iterations, residuals, extent));
  if (with_contacts)
    plots.push_back(value_plot(list, {left, y + height, right, bottom}, t,
                               "active set (contact pairs)", x_axis, iterations, active,
                               extent.largest_active_set, palette::contact, true, true));
}

}  // namespace

DrawList draw_overlay(const OverlayInfo& info, const solver::Model& model,
                      const solver::Snapshot& snapshot,
                      const std::vector<solver::HistoryEntry>& history, const RunExtent& extent,
                      const View& view, const StepSeries* steps, std::vector<PlotArea>* areas) {
  std::vector<PlotArea> ignored;
  std::vector<PlotArea>& plots = areas ? *areas : ignored;
  DrawList list;
  const Rect panel = overlay_panel(view);
  const float t = text_size(view);
  const float pad = 0.6f * t;
  list.rect(panel, palette::panel);
  list.rect_outline(panel, 1.0f, palette::grid);
  const float y = draw_overlay_rows(list, info, model, snapshot, view, panel);
  const Rect plot_region{panel.x0 + pad - 0.2f * t, y, panel.x1 - pad, panel.y1 - pad};
  if (steps && !steps->all.empty())
    draw_step_plots(list, plot_region, t, model, *steps, plots);
  else
    draw_iteration_plots(list, plot_region, t, !model.pairs.empty(), history, extent, plots);
  return list;
}

}  // namespace fetic::render
