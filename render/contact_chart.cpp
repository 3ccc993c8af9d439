#include "render/contact_chart.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "render/colormap.hpp"
#include "render/plot.hpp"
#include "render/text_format.hpp"
#include "scenes/units.hpp"

namespace fetic::render {
namespace {

struct PairValues {
  std::vector<double> force, gap;  // per pair: contact force, current gap
  std::vector<bool> active;
};

PairValues pair_values(const solver::Model& model, const solver::Snapshot& snapshot) {
  const auto u = solver::strut_displacements(model, snapshot);
  PairValues values;
  for (std::size_t k = 0; k < model.pairs.size(); ++k) {
    const solver::ContactPair& pair = model.pairs[k];
    const solver::Vec2 ua =
        u[static_cast<std::size_t>(pair.strut_a)][static_cast<std::size_t>(pair.node_a)];
    const solver::Vec2 ub =
        u[static_cast<std::size_t>(pair.strut_b)][static_cast<std::size_t>(pair.node_b)];
    values.force.push_back(k < snapshot.force.size() ? snapshot.force[k] : 0.0);
    values.gap.push_back(pair.gap - (ua - ub).dot(pair.normal));
    values.active.push_back(k < snapshot.in_working_set.size() && snapshot.in_working_set[k]);
  }
  return values;
}

// One strip: axes over pairs 0 .. n-1 and a bar from 0 to each value.
// `inner_left`: where the plot box should start (the strips line up their pairs); 0: where
// the frame and its tick labels put it.
PlotArea draw_strip(DrawList& list, const Rect& frame, float text, const std::string& title,
                    const std::string& x_label, const std::vector<double>& values, double divisor,
                    Color color, float inner_left = 0.0f) {
  PlotSpec spec;
  spec.frame = frame;
  spec.text_size = text;
  spec.title = title;
  spec.x = {x_label, -0.5, static_cast<double>(values.size()) - 0.5, false, true};
  Series range;  // only to fix the y range: 0 and every value
  range.x = {0.0};
  range.y = {0.0};
  for (const double v : values)
    if (std::isfinite(v)) range.y.push_back(v / divisor);
  range.x.resize(range.y.size(), 0.0);
  range.width = 0.0f;
  spec.series.push_back(range);
  spec.legend = Corner::TopRight;
  if (inner_left > 0.0f) {  // measured without drawing, then moved to start there
    DrawList scratch;
    spec.frame.x0 += std::max(0.0f, inner_left - draw_axes(scratch, spec).inner().x0);
  }
  const PlotArea area = draw_axes(list, spec);
  const Rect& box = area.inner();
  const float bar = std::max(1.0f, 0.8f * box.width() / static_cast<float>(values.size()));
  const float zero = area.to_pixel(0.0, 0.0).y;
  for (std::size_t k = 0; k < values.size(); ++k) {
    if (!std::isfinite(values[k]) || values[k] == 0.0) continue;
    const Point top = area.to_pixel(static_cast<double>(k), values[k] / divisor);
    const float from = std::clamp(zero, box.y0, box.y1);
    float to = std::clamp(top.y, box.y0, box.y1);
    if (std::abs(to - from) < 1.0f) to = from + (values[k] > 0.0 ? -1.0f : 1.0f);  // visible
    list.line({top.x, from}, {top.x, to}, bar, color);
  }
  if (zero > box.y0 && zero < box.y1) list.line({box.x0, zero}, {box.x1, zero}, 1.0f, palette::ink);
  return area;
}

}  // namespace

bool chart_shown(const solver::Model& model, int wanted) {
  if (model.pairs.empty()) return false;
  if (wanted >= 0) return wanted > 0;
  return static_cast<int>(model.pairs.size()) >= kChartPairs;
}

DrawList draw_contact_chart(const solver::Model& model, const solver::Snapshot& snapshot,
                            const Rect& region, float text_size) {
  DrawList list;
  if (model.pairs.empty() || region.width() < 4.0f * text_size) return list;
  const PairValues values = pair_values(model, snapshot);
  const float t = 0.85f * text_size;
  list.rect(region, palette::panel);
  list.rect_outline(region, 1.0f, palette::grid);

  double largest_force = 0.0, largest_gap = 0.0;
  int active = 0;
  for (std::size_t k = 0; k < values.force.size(); ++k) {
    if (std::isfinite(values.force[k]))
      largest_force = std::max(largest_force, std::abs(values.force[k]));
    if (std::isfinite(values.gap[k])) largest_gap = std::max(largest_gap, std::abs(values.gap[k]));
    active += values.active[k] ? 1 : 0;
  }
  const scenes::DisplayUnit force_unit =
      scenes::display_unit(scenes::Quantity::Force, model.units, largest_force);
  const scenes::DisplayUnit gap_unit =
      scenes::display_unit(scenes::Quantity::Length, model.units, largest_gap);
  const std::string pairs = std::to_string(values.force.size());

  // Force on top, then a row of active marks, then the current gap.
  const float pad = 0.4f * t;
  const float marks = 0.9f * t;
  const float half = 0.5f * (region.height() - marks - 2.0f * pad);
  const Rect force_frame{region.x0 + pad, region.y0 + pad, region.x1 - pad, region.y0 + pad + half};
  const Rect gap_frame{region.x0 + pad, force_frame.y1 + marks, region.x1 - pad, region.y1 - pad};
  // Both strips' boxes start where the wider tick labels need, so a pair's bars line up.
  const std::string force_title = "contact force per pair [" + force_unit.name + "]";
  const std::string gap_title = "current gap [" + gap_unit.name +
                                "]; active (red): " + std::to_string(active) + " of " + pairs;
  const std::string x_label = "pair (result file order)";
  DrawList scratch;
  const float left = std::max(draw_strip(scratch, force_frame, t, force_title, "", values.force,
                                         force_unit.divisor, palette::force)
                                  .inner()
                                  .x0,
                              draw_strip(scratch, gap_frame, t, gap_title, x_label, values.gap,
                                         gap_unit.divisor, palette::gap)
                                  .inner()
                                  .x0);
  const PlotArea forces = draw_strip(list, force_frame, t, force_title, "", values.force,
                                     force_unit.divisor, palette::force, left);
  draw_strip(list, gap_frame, t, gap_title, x_label, values.gap, gap_unit.divisor, palette::gap,
             left);
  // The active pairs: a red tick per pair under the force strip, at the x of its bar.
  const float y0 = force_frame.y1 + 0.1f * marks, y1 = force_frame.y1 + 0.8f * marks;
  const float tick =
      std::max(1.0f, 0.8f * forces.inner().width() / static_cast<float>(values.force.size()));
  for (std::size_t k = 0; k < values.active.size(); ++k)
    if (values.active[k]) {
      const float x = forces.to_pixel(static_cast<double>(k), 0.0).x;
      list.line({x, y0}, {x, y1}, tick, palette::contact);
    }
  return list;
}

}  // namespace fetic::render
