#include "render/plot.hpp"

#include <algorithm>
#include <cmath>

#include "render/colormap.hpp"
#include "render/text_format.hpp"

namespace fetic::render {
namespace {

double nice_step(double raw, bool integer) {
  if (!(raw > 0.0) || !std::isfinite(raw)) return 1.0;
  const double decade = std::pow(10.0, std::floor(std::log10(raw)));
  double step = 10.0 * decade;
  for (double mantissa : {1.0, 2.0, 5.0})
    if (mantissa * decade >= raw * (1.0 - 1e-9)) {
      step = mantissa * decade;
      break;
    }
  return integer ? std::max(1.0, std::round(step)) : step;
}

std::string linear_label(double value, double step, double largest) {
  if (std::abs(value) < 1e-9 * step) return "0";
  if (largest >= 1e5 || step < 1e-4) return format("%.3g", value);
  const int decimals = std::max(0, static_cast<int>(-std::floor(std::log10(step) + 1e-9)));
  char pattern[16];
  std::snprintf(pattern, sizeof pattern, "%%.%df", decimals);
  return format(pattern, value);
}

// Clips segment a-b to the rectangle (Liang-Barsky); false when nothing is left.
bool clip(Point& a, Point& b, const Rect& r) {
  double t0 = 0.0, t1 = 1.0;
  const double dx = b.x - a.x, dy = b.y - a.y;
  const double p[4] = {-dx, dx, -dy, dy};
  const double q[4] = {a.x - r.x0, r.x1 - a.x, a.y - r.y0, r.y1 - a.y};
  for (int i = 0; i < 4; ++i) {
    if (p[i] == 0.0) {
      if (q[i] < 0.0) return false;
      continue;
    }
    const double t = q[i] / p[i];
    if (p[i] < 0.0)
      t0 = std::max(t0, t);
    else
      t1 = std::min(t1, t);
  }
  if (t0 > t1) return false;
  const Point start = a;
  a = {static_cast<float>(start.x + t0 * dx), static_cast<float>(start.y + t0 * dy)};
  b = {static_cast<float>(start.x + t1 * dx), static_cast<float>(start.y + t1 * dy)};
  return true;
}

std::vector<double> all_values(const std::vector<Series>& series, bool x) {
  std::vector<double> values;
  for (const Series& s : series)
    values.insert(values.end(), (x ? s.x : s.y).begin(), (x ? s.x : s.y).end());
  return values;
}

std::vector<Tick> ticks_for(const Axis& axis, double min, double max, int target) {
  return axis.log ? log_ticks(min, max, target) : linear_ticks(min, max, target, axis.integer);
}

}  // namespace

std::vector<Tick> linear_ticks(double min, double max, int target_count, bool integer) {
  std::vector<Tick> ticks;
  if (!(max > min)) return {{min, linear_label(min, 1.0, std::abs(min)), true}};
  const double step = nice_step((max - min) / std::max(1, target_count), integer);
  const double largest = std::max(std::abs(min), std::abs(max));
  for (double k = std::ceil(min / step - 1e-9); k * step <= max + 1e-9 * step; k += 1.0) {
    double value = k * step;
    if (std::abs(value) < 1e-12 * step) value = 0.0;
    ticks.push_back({value, linear_label(value, step, largest), true});
  }
  return ticks;
}

std::vector<Tick> log_ticks(double min, double max, int target_count) {
  std::vector<Tick> ticks;
  if (!(min > 0.0) || !(max > min)) return ticks;
  const int low = static_cast<int>(std::floor(std::log10(min) + 1e-9));
  const int high = static_cast<int>(std::ceil(std::log10(max) - 1e-9));
  const int decades = std::max(1, high - low);
  const int stride = std::max(1, (decades + target_count - 1) / std::max(1, target_count));
  for (int e = low; e <= high; ++e) {
    const double decade = std::pow(10.0, e);
    if ((e - low) % stride == 0 && decade >= min * (1 - 1e-9) && decade <= max * (1 + 1e-9))
      ticks.push_back({decade, power_of_ten(e), true});
    if (stride == 1 && decades <= 4)
      for (int m = 2; m <= 9; ++m)
        if (m * decade > min && m * decade < max) ticks.push_back({m * decade, "", false});
  }
  return ticks;
}

void nice_range(const Axis& axis, double& min, double& max, const std::vector<double>& data) {
  double low = std::numeric_limits<double>::infinity(), high = -low;
  for (double v : data)
    if (std::isfinite(v) && (!axis.log || v > 0.0)) {
      low = std::min(low, v);
      high = std::max(high, v);
    }
  if (std::isfinite(axis.min)) low = axis.min;
  if (std::isfinite(axis.max)) high = axis.max;
  if (!std::isfinite(low) || !std::isfinite(high)) {
    low = axis.log ? 0.1 : 0.0;
    high = axis.log ? 10.0 : 1.0;
  }
  if (axis.log) {
    low = std::max(low, 1e-300);
    high = std::max(high, low);
    if (!std::isfinite(axis.min)) low = std::pow(10.0, std::floor(std::log10(low) + 1e-9));
    if (!std::isfinite(axis.max)) high = std::pow(10.0, std::ceil(std::log10(high) - 1e-9));
    if (high <= low) high = low * 10.0;
  } else {
    if (high <= low) {
      const double pad = low == 0.0 ? 1.0 : 0.1 * std::abs(low);
      low -= std::isfinite(axis.min) ? 0.0 : pad;
      high += pad;
    }
    const double step = nice_step((high - low) / 5.0, axis.integer);
    if (!std::isfinite(axis.min)) low = std::floor(low / step + 1e-9) * step;
    if (!std::isfinite(axis.max)) high = std::ceil(high / step - 1e-9) * step;
  }
  min = low;
  max = high;
}

PlotArea::PlotArea(Rect inner, double x0, double x1, double y0, double y1, bool log_x, bool log_y)
    : inner_(inner), x0_(x0), x1_(x1), y0_(y0), y1_(y1), log_x_(log_x), log_y_(log_y) {}

Point PlotArea::to_pixel(double x, double y) const {
  const auto unit = [](double v, double a, double b, bool log) {
    if (log) return (std::log10(v) - std::log10(a)) / (std::log10(b) - std::log10(a));
    return (v - a) / (b - a);
  };
  return {inner_.x0 + static_cast<float>(unit(x, x0_, x1_, log_x_) * inner_.width()),
          inner_.y1 - static_cast<float>(unit(y, y0_, y1_, log_y_) * inner_.height())};
}

PlotArea draw_axes(DrawList& list, const PlotSpec& spec) {
  const float t = spec.text_size;
  const float label_size = 0.9f * t;
  double x0, x1, y0, y1;
  nice_range(spec.x, x0, x1, all_values(spec.series, true));
  nice_range(spec.y, y0, y1, all_values(spec.series, false));

  // Room for the y tick labels: as wide as the widest of them.
  float y_label_width = 0.0f;
  for (const Tick& tick : ticks_for(spec.y, y0, y1, 6))
    y_label_width = std::max(y_label_width, estimated_text_width(tick.label, label_size));
  Rect inner = spec.frame;
  inner.y0 += spec.title.empty() ? 0.6f * t : 1.7f * t;
  inner.y1 -= 1.6f * t + (spec.x.label.empty() ? 0.0f : 1.3f * t);
  inner.x0 += y_label_width + 0.7f * t + (spec.y.label.empty() ? 0.0f : 1.4f * t);
  inner.x1 -= 0.8f * t;
  inner.x1 = std::max(inner.x1, inner.x0 + 1.0f);
  inner.y1 = std::max(inner.y1, inner.y0 + 1.0f);

  if (spec.equal_aspect && !spec.x.log && !spec.y.log) {
    const double per_x = (x1 - x0) / inner.width(), per_y = (y1 - y0) / inner.height();
    if (per_x > per_y) {
      const double grow = 0.5 * (per_x * inner.height() - (y1 - y0));
      y0 -= grow;
      y1 += grow;
    } else {
      const double grow = 0.5 * (per_y * inner.width() - (x1 - x0));
      x0 -= grow;
      x1 += grow;
    }
  }
  const PlotArea area(inner, x0, x1, y0, y1, spec.x.log, spec.y.log);

  // Lines grow with the text (1 pixel at 12-pixel labels).
  const float u = std::max(1.0f, t / 12.0f);
  list.rect(inner, {255, 255, 255, 255});
  const int x_target = std::clamp(static_cast<int>(inner.width() / (4.5f * t)), 2, 8);
  const int y_target = std::clamp(static_cast<int>(inner.height() / (2.2f * t)), 2, 8);
  const auto x_ticks = ticks_for(spec.x, x0, x1, x_target);
  const auto y_ticks = ticks_for(spec.y, y0, y1, y_target);
  const float tick = 0.35f * t;
  for (const Tick& x : x_ticks) {
    const float px = area.to_pixel(x.value, spec.y.log ? y0 : y0).x;
    if (px < inner.x0 - 0.5f || px > inner.x1 + 0.5f) continue;
    if (spec.grid && x.major) list.line({px, inner.y0}, {px, inner.y1}, u, palette::grid);
    list.line({px, inner.y1}, {px, inner.y1 - (x.major ? tick : 0.5f * tick)}, u, palette::ink);
    if (!x.label.empty())
      list.text(x.label, {px, inner.y1 + 0.3f * t}, label_size, palette::ink, HAlign::Center,
                VAlign::Top);
  }
  for (const Tick& y : y_ticks) {
    const float py = area.to_pixel(x0, y.value).y;
    if (py < inner.y0 - 0.5f || py > inner.y1 + 0.5f) continue;
    if (spec.grid && y.major) list.line({inner.x0, py}, {inner.x1, py}, u, palette::grid);
    list.line({inner.x0, py}, {inner.x0 + (y.major ? tick : 0.5f * tick), py}, u, palette::ink);
    if (!y.label.empty())
      list.text(y.label, {inner.x0 - 0.35f * t, py}, label_size, palette::ink, HAlign::Right,
                VAlign::Middle);
  }
  list.rect_outline(inner, u, palette::ink);

  if (!spec.title.empty())
    list.text(spec.title, {0.5f * (inner.x0 + inner.x1), spec.frame.y0 + 0.2f * t}, t, palette::ink,
              HAlign::Center, VAlign::Top, true);
  if (!spec.x.label.empty())
    list.text(spec.x.label, {0.5f * (inner.x0 + inner.x1), spec.frame.y1 - 0.1f * t}, label_size,
              palette::ink, HAlign::Center, VAlign::Bottom);
  if (!spec.y.label.empty()) {
    TextItem label;
    label.text = spec.y.label;
    label.anchor = {spec.frame.x0 + 0.1f * t, 0.5f * (inner.y0 + inner.y1)};
    label.size = label_size;
    label.color = palette::ink;
    label.h_align = HAlign::Center;
    label.v_align = VAlign::Top;
    label.vertical = true;
    list.text(std::move(label));
  }
  return area;
}

void draw_series(DrawList& list, const PlotArea& area, const Series& series) {
  std::vector<std::pair<double, double>> points;
  const std::size_t n = std::min(series.x.size(), series.y.size());
  for (std::size_t i = 0; i < n; ++i) {
    if (series.steps && i > 0) points.emplace_back(series.x[i], series.y[i - 1]);
    points.emplace_back(series.x[i], series.y[i]);
  }
  const auto usable = [&](const std::pair<double, double>& p) {
    return std::isfinite(p.first) && std::isfinite(p.second) && (!area.log_y() || p.second > 0.0);
  };
  const Rect& box = area.inner();
  for (std::size_t i = 0; i + 1 < points.size(); ++i) {
    if (!usable(points[i]) || !usable(points[i + 1])) continue;
    Point a = area.to_pixel(points[i].first, points[i].second);
    Point b = area.to_pixel(points[i + 1].first, points[i + 1].second);
    const bool joint = i > 0 && usable(points[i - 1]) && box.contains(a);
    if (clip(a, b, box)) {
      list.line(a, b, series.width, series.color);
      if (joint && series.width > 2.0f) list.disc(a, series.width / 2, series.color);
    }
  }
  if (series.markers)
    for (std::size_t i = 0; i < n; ++i) {
      if (!usable({series.x[i], series.y[i]})) continue;
      const Point p = area.to_pixel(series.x[i], series.y[i]);
      if (box.contains(p)) list.disc(p, 1.3f * series.width + 1.0f, series.color);
    }
}

void draw_legend(DrawList& list, const PlotArea& area, const std::vector<Series>& series,
                 Corner corner, float text_size) {
  std::vector<const Series*> named;
  for (const Series& s : series)
    if (!s.name.empty()) named.push_back(&s);
  if (named.empty()) return;
  const float t = 0.85f * text_size;
  const float sample = 1.8f * t, row = 1.35f * t, pad = 0.5f * t;
  float text_width = 0.0f;
  for (const Series* s : named)
    text_width = std::max(text_width, estimated_text_width(s->name, t));
  const float width = pad + sample + 0.5f * t + text_width + pad;
  const float height = pad + row * static_cast<float>(named.size()) + pad - 0.35f * t;
  const Rect& inner = area.inner();
  const float margin = 0.5f * text_size;
  const bool left = corner == Corner::TopLeft || corner == Corner::BottomLeft;
  const bool top = corner == Corner::TopLeft || corner == Corner::TopRight;
  const float x0 = left ? inner.x0 + margin : inner.x1 - margin - width;
  const float y0 = top ? inner.y0 + margin : inner.y1 - margin - height;
  const Rect box{x0, y0, x0 + width, y0 + height};
  list.rect(box, {255, 255, 255, 235});
  list.rect_outline(box, 1.0f, palette::grid);
  for (std::size_t i = 0; i < named.size(); ++i) {
    const float y = y0 + pad + row * static_cast<float>(i) + 0.5f * t;
    list.line({x0 + pad, y}, {x0 + pad + sample, y}, named[i]->width, named[i]->color);
    if (named[i]->markers)
      list.disc({x0 + pad + 0.5f * sample, y}, 1.3f * named[i]->width + 1.0f, named[i]->color);
    list.text(named[i]->name, {x0 + pad + sample + 0.5f * t, y}, t, palette::ink, HAlign::Left,
              VAlign::Middle);
  }
}

DrawList draw_plot(const PlotSpec& spec) {
  DrawList list;
  const PlotArea area = draw_axes(list, spec);
  for (const Series& series : spec.series)
    draw_series(list, area, series);
  draw_legend(list, area, spec.series, spec.legend, spec.text_size);
  return list;
}

}  // namespace fetic::render
