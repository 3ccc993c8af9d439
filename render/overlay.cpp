#include "render/overlay.hpp"

#include <algorithm>
#include <cmath>

#include "render/colormap.hpp"
#include "render/plot.hpp"
#include "render/text_format.hpp"

namespace fetic::render {

Rect overlay_panel(const View& view) {
  const auto width = static_cast<float>(view.width), height = static_cast<float>(view.height);
  const float panel = std::clamp(0.28f * width, 150.0f, 360.0f);
  const float margin = std::max(4.0f, 0.5f * base_text_size(view.width, view.height));
  return {width - panel - margin, margin, width - margin, height - margin};
}

Rect scene_region(const View& view) {
  const auto width = static_cast<float>(view.width), height = static_cast<float>(view.height);
  if (!view.show_overlay) return {0.0f, 0.0f, width, height};
  return {0.0f, 0.0f, overlay_panel(view).x0, height};
}

DrawList draw_overlay(const OverlayInfo& info, const solver::Model& model,
                      const solver::Snapshot& snapshot,
                      const std::vector<solver::HistoryEntry>& history, const RunExtent& extent,
                      const View& view) {
  DrawList list;
  const Rect panel = overlay_panel(view);
  const float t = base_text_size(view.width, view.height);
  const float pad = 0.6f * t;
  list.rect(panel, palette::panel);
  list.rect_outline(panel, 1.0f, palette::grid);

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
        palette::contact);
  const Color status_color = snapshot.status == solver::Status::Failed      ? palette::contact
                             : snapshot.status == solver::Status::Converged ? Color{0, 130, 70, 255}
                                                                            : palette::ink;
  row("status", info.status.empty() ? solver::to_string(snapshot.status) : info.status,
      status_color);
  row("colour",
      view.color_by == ColorBy::Stress  ? "axial stress"
      : view.color_by == ColorBy::Strut ? "struts"
                                        : "subdomains",
      palette::ink);
  y += 0.4f * t;

  // Plots: iteration on x, fixed to the whole run so that frames line up.
  std::vector<double> iterations, residuals, active;
  for (const solver::HistoryEntry& entry : history) {
    iterations.push_back(entry.iteration);
    residuals.push_back(entry.residual);
    active.push_back(entry.active_set);
  }
  const bool with_active = !model.pairs.empty();
  const float plot_text = 0.85f * t;
  const float room = panel.y1 - pad - y;
  const float plot_height = with_active ? 0.5f * room : room;
  Axis x_axis{"iteration", 0.0, std::max(1.0, static_cast<double>(extent.largest_iteration)), false,
              true};

  PlotSpec residual_plot;
  residual_plot.frame = {x0 - 0.2f * t, y, x1, y + plot_height};
  residual_plot.title = "relative residual";
  residual_plot.text_size = plot_text;
  residual_plot.x = x_axis;
  residual_plot.x.label.clear();
  residual_plot.y.log = true;
  if (extent.smallest_residual > 0.0) {
    residual_plot.y.min = std::pow(10.0, std::floor(std::log10(extent.smallest_residual)));
    residual_plot.y.max = std::pow(10.0, std::ceil(std::log10(extent.largest_residual)));
    if (residual_plot.y.max <= residual_plot.y.min)
      residual_plot.y.max = 10.0 * residual_plot.y.min;
  }
  residual_plot.series.push_back({"", iterations, residuals, series_color(0), 1.8f, false, false});
  const PlotArea area = draw_axes(list, residual_plot);
  draw_series(list, area, residual_plot.series.front());
  if (!history.empty() && residuals.back() > 0.0) {
    const Point current = area.to_pixel(iterations.back(), residuals.back());
    if (area.inner().contains(current)) list.disc(current, 3.0f, series_color(0));
  }

  if (with_active) {
    PlotSpec active_plot;
    active_plot.frame = {x0 - 0.2f * t, y + plot_height, x1, panel.y1 - pad};
    active_plot.title = "active set (contact pairs)";
    active_plot.text_size = plot_text;
    active_plot.x = x_axis;
    active_plot.y = {"", 0.0, std::max(1.0, static_cast<double>(extent.largest_active_set)), false,
                     true};
    active_plot.series.push_back({"", iterations, active, palette::contact, 1.8f, false, true});
    const PlotArea active_area = draw_axes(list, active_plot);
    draw_series(list, active_area, active_plot.series.front());
    if (!history.empty())
      list.disc(active_area.to_pixel(iterations.back(), active.back()), 3.0f, palette::contact);
  }
  return list;
}

}  // namespace fetic::render
