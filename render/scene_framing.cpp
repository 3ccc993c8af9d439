#include "render/scene_framing.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>

namespace fetic::render {
namespace {

using solver::Vec2;

struct Bounds {
  Vec2 low{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
  Vec2 high = -low;
  void include(const Vec2& p) {
    low = low.cwiseMin(p);
    high = high.cwiseMax(p);
  }
  bool valid() const { return low.x() <= high.x() && low.y() <= high.y(); }
};

double largest_gap(const solver::Model& model) {
  double largest = 0.0;
  for (const solver::ContactPair& pair : model.pairs)
    largest = std::max(largest, pair.gap);
  return largest;
}

// Smallest distance between the axes of two parallel struts that lie side by side (their
// extents along the axis overlap): bars must be thinner than that on screen.
double smallest_side_by_side_distance(const solver::Model& model) {
  double smallest = std::numeric_limits<double>::infinity();
  const std::size_t n = std::min<std::size_t>(model.struts.size(), 2000);
  for (std::size_t a = 0; a < n; ++a)
    for (std::size_t b = a + 1; b < n; ++b) {
      const solver::StrutMesh& sa = model.struts[a];
      const solver::StrutMesh& sb = model.struts[b];
      if (std::abs(sa.e1.x() * sb.e1.y() - sa.e1.y() * sb.e1.x()) > 1e-6) continue;
      const Vec2 d = sb.origin - sa.origin;
      const double across = std::abs(d.dot(sa.e2));
      if (across <= 1e-12) continue;
      const double b0 = d.dot(sa.e1), b1 = (sb.origin + sb.length * sb.e1 - sa.origin).dot(sa.e1);
      if (std::max(b0, b1) < 0.0 || std::min(b0, b1) > sa.length) continue;
      smallest = std::min(smallest, across - 0.5 * (sa.height + sb.height));
    }
  return smallest;
}

}  // namespace

Point SceneFraming::to_pixel(const Vec2& world) const {
  return {pixel_center.x + static_cast<float>((world.x() - world_center.x()) * pixels_per_unit),
          pixel_center.y - static_cast<float>((world.y() - world_center.y()) * pixels_per_unit)};
}

Point SceneFraming::direction(const Vec2& world) const {
  return normalized(Point{static_cast<float>(world.x()), static_cast<float>(-world.y())});
}

Point SceneFraming::node(const solver::Model& model, int strut, int node, const Vec2& u) const {
  const solver::StrutMesh& mesh = model.struts[static_cast<std::size_t>(strut)];
  return to_pixel(mesh.nodes[static_cast<std::size_t>(node)] +
                  strut_offset[static_cast<std::size_t>(strut)] + magnification * u);
}

double round_magnification(double raw) {
  if (!(raw > 0.0) || !std::isfinite(raw)) return 1.0;
  const double decade = std::pow(10.0, std::floor(std::log10(raw)));
  for (double mantissa : {5.0, 2.0, 1.0})
    if (mantissa * decade <= raw * (1.0 + 1e-9)) return mantissa * decade;
  return decade;
}

std::vector<Vec2> gap_offsets(const solver::Model& model, double magnification) {
  const std::size_t n = model.struts.size();
  std::vector<Vec2> offset(n, Vec2::Zero());
  if (magnification == 1.0) return offset;
  // Contact graph: per strut its contacts (mean gap over the pairs of a contact).
  struct Edge {
    int other;
    Vec2 shift;  // offset[other] - offset[this]
  };
  std::vector<std::vector<Edge>> edges(n);
  for (std::size_t c = 0; c + 1 < model.contact_first_pair.size(); ++c) {
    const int first = model.contact_first_pair[c], last = model.contact_first_pair[c + 1];
    if (first >= last) continue;
    double gap = 0.0;
    for (int p = first; p < last; ++p)
      gap += model.pairs[static_cast<std::size_t>(p)].gap;
    gap /= (last - first);
    const solver::ContactPair& pair = model.pairs[static_cast<std::size_t>(first)];
    const Vec2 shift = (magnification - 1.0) * gap * pair.normal;
    edges[static_cast<std::size_t>(pair.strut_a)].push_back({pair.strut_b, shift});
    edges[static_cast<std::size_t>(pair.strut_b)].push_back({pair.strut_a, -shift});
  }
  // Breadth-first from clamped struts first, so that supports of a group stay in place
  // where they can.
  std::vector<char> placed(n, 0);
  std::vector<std::size_t> roots;
  for (std::size_t s = 0; s < n; ++s)
    if (!model.floating(static_cast<int>(s))) roots.push_back(s);
  for (std::size_t s = 0; s < n; ++s)
    if (model.floating(static_cast<int>(s))) roots.push_back(s);
  for (std::size_t root : roots) {
    if (placed[root]) continue;
    placed[root] = 1;
    std::queue<std::size_t> queue;
    queue.push(root);
    while (!queue.empty()) {
      const std::size_t s = queue.front();
      queue.pop();
      for (const Edge& edge : edges[s]) {
        const auto other = static_cast<std::size_t>(edge.other);
        if (placed[other]) continue;
        placed[other] = 1;
        offset[other] = offset[s] + edge.shift;
        queue.push(other);
      }
    }
  }
  return offset;
}

double automatic_magnification(const solver::Model& model, const RunExtent& extent,
                               bool magnify_gaps) {
  Bounds bounds;
  for (const solver::StrutMesh& mesh : model.struts)
    for (const Vec2& p : mesh.nodes)
      bounds.include(p);
  if (!bounds.valid()) return 1.0;
  const double size = (bounds.high - bounds.low).maxCoeff();
  const double small =
      std::max(extent.largest_displacement, magnify_gaps ? largest_gap(model) : 0.0);
  if (!(small > 0.0) || !(size > 0.0)) return 1.0;
  return round_magnification(0.08 * size / small);
}

SceneFraming frame_scene(const solver::Model& model, const View& view, const RunExtent& extent,
                         const Rect& region) {
  SceneFraming framing;
  framing.region = region;
  framing.text_size = base_text_size(view.width, view.height);
  framing.magnification = view.magnification > 0.0
                              ? view.magnification
                              : automatic_magnification(model, extent, view.magnify_gaps);
  framing.gaps_magnified =
      view.magnify_gaps && framing.magnification != 1.0 && !model.pairs.empty();
  framing.strut_offset = view.magnify_gaps ? gap_offsets(model, framing.magnification)
                                           : std::vector<Vec2>(model.struts.size(), Vec2::Zero());
  framing.force_scale = extent.largest_force;
  framing.stress_scale = extent.largest_stress;
  for (std::size_t s = 0; s < model.struts.size(); ++s) {
    const Eigen::VectorXd& load = model.loads[s];
    const int dofs = model.struts[s].dofs_per_node;
    for (int n = 0; n + dofs <= load.size(); n += dofs)
      framing.load_scale = std::max(framing.load_scale, load.segment(n, dofs).norm());
  }

  // Reference geometry with its shifts, widened by the largest magnified displacement.
  Bounds bounds;
  for (std::size_t s = 0; s < model.struts.size(); ++s) {
    const solver::StrutMesh& mesh = model.struts[s];
    for (const Vec2& p : mesh.nodes)
      bounds.include(p + framing.strut_offset[s]);
  }
  if (!bounds.valid()) bounds.include(Vec2::Zero());
  const double reach = framing.magnification * extent.largest_displacement;
  bounds.low -= Vec2(reach, reach);
  bounds.high += Vec2(reach, reach);

  // Room for supports, load arrows and glyphs around the geometry.
  const float margin = 2.8f * framing.text_size;
  const double room_x = std::max(1.0f, region.width() - 2 * margin);
  const double room_y = std::max(1.0f, region.height() - 2 * margin);
  const Vec2 size = bounds.high - bounds.low;
  double scale = std::numeric_limits<double>::infinity();
  if (size.x() > 0.0) scale = std::min(scale, room_x / size.x());
  if (size.y() > 0.0) scale = std::min(scale, room_y / size.y());
  if (!std::isfinite(scale)) scale = 1.0;
  framing.pixels_per_unit = scale;
  framing.world_center = 0.5 * (bounds.low + bounds.high);
  framing.pixel_center = {0.5f * (region.x0 + region.x1), 0.5f * (region.y0 + region.y1)};

  const double apart = smallest_side_by_side_distance(model);
  if (std::isfinite(apart) && apart > 0.0) framing.lane = static_cast<float>(apart * scale);
  float width = view.bar_width;
  if (width <= 0.0f)
    width = std::min(std::clamp(std::min(region.width(), region.height()) / 100.0f, 3.0f, 9.0f),
                     std::max(2.0f, 0.5f * framing.lane));
  framing.bar_width = width;
  place_view(framing, view);
  return framing;
}

void place_view(SceneFraming& framing, const View& view) {
  framing.pixels_per_unit *= view.zoom;
  if (!view.centered) return;
  const Point middle{0.5f * (framing.region.x0 + framing.region.x1),
                     0.5f * (framing.region.y0 + framing.region.y1)};
  const Point at = framing.to_pixel(Vec2(view.center_x, view.center_y));
  framing.pixel_center = {middle.x - (at.x - framing.pixel_center.x),
                          middle.y - (at.y - framing.pixel_center.y)};
}

}  // namespace fetic::render
