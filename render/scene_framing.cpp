#include "render/scene_framing.hpp"

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

namespace fetic::render {
namespace {

using solver::Vec2;
constexpr double kInfinity = std::numeric_limits<double>::infinity();

struct Bounds {
  Vec2 low{kInfinity, kInfinity};
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

// Where a node lies along its strut: 0 at 'from', 1 at 'to'.
double axial_position(const solver::StrutMesh& mesh, int node) {
  if (!(mesh.length > 0.0)) return 0.0;
  const double xi =
      (mesh.nodes[static_cast<std::size_t>(node)] - mesh.origin).dot(mesh.e1) / mesh.length;
  return std::clamp(xi, 0.0, 1.0);
}

double median_length(const solver::Model& model) {
  std::vector<double> lengths;
  for (const solver::StrutMesh& mesh : model.struts)
    if (mesh.length > 0.0) lengths.push_back(mesh.length);
  if (lengths.empty()) return 1.0;
  std::nth_element(lengths.begin(), lengths.begin() + static_cast<long>(lengths.size() / 2),
                   lengths.end());
  return lengths[lengths.size() / 2];
}

}  // namespace

Point SceneFraming::to_pixel(const Vec2& world) const {
  return {pixel_center.x + static_cast<float>((world.x() - world_center.x()) * pixels_per_unit),
          pixel_center.y - static_cast<float>((world.y() - world_center.y()) * pixels_per_unit)};
}

Point SceneFraming::direction(const Vec2& world) const {
  return normalized(Point{static_cast<float>(world.x()), static_cast<float>(-world.y())});
}

Vec2 SceneFraming::drawn(const solver::Model& model, int strut, int node, const Vec2& u) const {
  const auto s = static_cast<std::size_t>(strut), n = static_cast<std::size_t>(node);
  Vec2 position = model.struts[s].nodes[n] + magnification * u;
  if (gaps_magnified && s < widening.size()) position += (magnification - 1.0) * widening[s][n];
  return position;
}

Point SceneFraming::node(const solver::Model& model, int strut, int node, const Vec2& u) const {
  return to_pixel(drawn(model, strut, node, u));
}

double round_magnification(double raw) {
  if (!(raw > 0.0) || !std::isfinite(raw)) return 1.0;
  const double decade = std::pow(10.0, std::floor(std::log10(raw)));
  for (double mantissa : {5.0, 2.0, 1.0})
    if (mantissa * decade <= raw * (1.0 + 1e-9)) return mantissa * decade;
  return decade;
}

std::vector<std::vector<Vec2>> gap_widening(const solver::Model& model) {
  const std::size_t n = model.struts.size();
  std::vector<std::vector<Vec2>> widening(n);
  for (std::size_t s = 0; s < n; ++s)
    widening[s].assign(model.struts[s].nodes.size(), Vec2::Zero());
  if (model.pairs.empty() || n == 0) return widening;

  // Unknowns: the axial shift of each strut's two ends (in units of the median strut
  // length), 2 s for 'from' and 2 s + 1 for 'to'. Least squares of weighted rows:
  // supports and contacts (weight kHard) against changes of strut length (weight 1).
  const double reference = median_length(model);
  constexpr double kHard = 1e6, kSmall = 1e-8;
  using Triplet = Eigen::Triplet<double>;
  std::vector<Triplet> normal;
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(static_cast<long>(2 * n));
  const auto row = [&](const std::vector<std::pair<int, double>>& terms, double value,
                       double weight) {
    for (const auto& [i, a] : terms) {
      rhs[i] += weight * a * value;
      for (const auto& [j, b] : terms)
        normal.emplace_back(i, j, weight * a * b);
    }
  };
  for (std::size_t s = 0; s < n; ++s) {
    const solver::StrutMesh& mesh = model.struts[s];
    const int from = static_cast<int>(2 * s), to = from + 1;
    const double stretch = mesh.length > 0.0 ? reference / mesh.length : 1.0;
    row({{from, -stretch}, {to, stretch}}, 0.0, 1.0);
    row({{from, 1.0}}, 0.0, kSmall);
    row({{to, 1.0}}, 0.0, kSmall);
    const auto& clamped = model.clamped_nodes[s];
    for (int node : clamped) {
      const double xi = axial_position(mesh, node);
      row({{from, 1.0 - xi}, {to, xi}}, 0.0, kHard);
    }
  }
  // Frame model: pinned ends stay like clamped ones, and the ends of a joint move together
  // (a joint is never drawn torn).
  for (std::size_t s = 0; s < model.end_supports.size() && s < n; ++s)
    for (int end = 0; end < 2; ++end)
      if (model.end_supports[s][static_cast<std::size_t>(end)] == solver::Support::Pinned)
        row({{static_cast<int>(2 * s) + end, 1.0}}, 0.0, kHard);
  for (const solver::JointLink& link : model.joints)
    for (std::size_t e = 1; e < link.ends.size(); ++e) {
      const auto [sa, na] = link.ends.front();
      const auto [sb, nb] = link.ends[e];
      const solver::StrutMesh& a = model.struts[static_cast<std::size_t>(sa)];
      const solver::StrutMesh& b = model.struts[static_cast<std::size_t>(sb)];
      const double xa = axial_position(a, na), xb = axial_position(b, nb);
      for (int c = 0; c < 2; ++c)
        row({{2 * sa, (1.0 - xa) * a.e1[c]},
             {2 * sa + 1, xa * a.e1[c]},
             {2 * sb, -(1.0 - xb) * b.e1[c]},
             {2 * sb + 1, -xb * b.e1[c]}},
            0.0, kHard);
    }
  for (std::size_t c = 0; c + 1 < model.contact_first_pair.size(); ++c) {
    const int first = model.contact_first_pair[c], last = model.contact_first_pair[c + 1];
    if (first >= last) continue;
    double gap = 0.0;
    for (int p = first; p < last; ++p)
      gap += model.pairs[static_cast<std::size_t>(p)].gap;
    gap /= (last - first);
    const solver::ContactPair& pair = model.pairs[static_cast<std::size_t>(first)];
    const solver::StrutMesh& a = model.struts[static_cast<std::size_t>(pair.strut_a)];
    const solver::StrutMesh& b = model.struts[static_cast<std::size_t>(pair.strut_b)];
    const double xa = axial_position(a, pair.node_a), xb = axial_position(b, pair.node_b);
    const double ca = a.e1.dot(pair.normal), cb = b.e1.dot(pair.normal);
    row({{2 * pair.strut_a, -(1.0 - xa) * ca},
         {2 * pair.strut_a + 1, -xa * ca},
         {2 * pair.strut_b, (1.0 - xb) * cb},
         {2 * pair.strut_b + 1, xb * cb}},
        gap / reference, kHard);
  }
  Eigen::SparseMatrix<double> matrix(static_cast<long>(2 * n), static_cast<long>(2 * n));
  matrix.setFromTriplets(normal.begin(), normal.end());
  const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(matrix);
  if (ldlt.info() != Eigen::Success) return widening;
  const Eigen::VectorXd x = ldlt.solve(rhs);
  if (!x.allFinite()) return widening;
  for (std::size_t s = 0; s < n; ++s) {
    const solver::StrutMesh& mesh = model.struts[s];
    for (int node = 0; node < mesh.node_count(); ++node) {
      const double xi = axial_position(mesh, node);
      widening[s][static_cast<std::size_t>(node)] =
          reference *
          ((1.0 - xi) * x[static_cast<long>(2 * s)] + xi * x[static_cast<long>(2 * s + 1)]) *
          mesh.e1;
    }
  }
  return widening;
}

std::vector<double> side_clearances(const solver::Model& model) {
  const std::size_t n = model.struts.size();
  std::vector<double> clearance(n, kInfinity);
  // Parallel struts, grouped by direction (an angle in [0, pi), to a micro-radian).
  std::map<long long, std::vector<std::size_t>> groups;
  for (std::size_t s = 0; s < n; ++s) {
    double angle = std::atan2(model.struts[s].e1.y(), model.struts[s].e1.x());
    if (angle < 0.0) angle += M_PI;
    if (angle >= M_PI - 5e-7) angle -= M_PI;
    groups[std::llround(angle * 1e6)].push_back(s);
  }
  for (auto& [key, members] : groups) {
    const solver::StrutMesh& first = model.struts[members.front()];
    const Vec2 along = first.e1, across = first.e2;
    const auto lateral = [&](std::size_t s) { return model.struts[s].origin.dot(across); };
    std::sort(members.begin(), members.end(),
              [&](std::size_t a, std::size_t b) { return lateral(a) < lateral(b); });
    const auto extent = [&](std::size_t s) {
      const solver::StrutMesh& m = model.struts[s];
      const double a = m.origin.dot(along), b = (m.origin + m.length * m.e1).dot(along);
      return std::pair{std::min(a, b), std::max(a, b)};
    };
    // For each strut, the nearest ones beside it among the next few in lateral order.
    constexpr std::size_t kLook = 64;
    for (std::size_t j = 0; j < members.size(); ++j) {
      const std::size_t sj = members[j];
      const auto [aj0, aj1] = extent(sj);
      for (std::size_t k = j + 1; k < members.size() && k <= j + kLook; ++k) {
        const std::size_t sk = members[k];
        const double distance = lateral(sk) - lateral(sj);
        if (distance <= 1e-12) continue;  // end to end on one axis
        const double free = distance - 0.5 * (model.struts[sj].height + model.struts[sk].height);
        if (free >= clearance[sj] && free >= clearance[sk]) break;
        const auto [ak0, ak1] = extent(sk);
        if (std::min(aj1, ak1) - std::max(aj0, ak0) <= 0.0) continue;  // not beside
        clearance[sj] = std::min(clearance[sj], free);
        clearance[sk] = std::min(clearance[sk], free);
      }
    }
  }
  return clearance;
}

MagnificationChoice automatic_magnification(const solver::Model& model, const RunExtent& extent,
                                            bool magnify_gaps,
                                            const std::vector<std::vector<Vec2>>& widening,
                                            const std::vector<double>& clearance) {
  Bounds bounds;
  for (const solver::StrutMesh& mesh : model.struts)
    for (const Vec2& p : mesh.nodes)
      bounds.include(p);
  if (!bounds.valid()) return {};
  const double size = (bounds.high - bounds.low).maxCoeff();
  const double small =
      std::max(extent.largest_displacement, magnify_gaps ? largest_gap(model) : 0.0);
  if (!(small > 0.0) || !(size > 0.0)) return {};
  MagnificationChoice choice;
  double raw = 0.08 * size / small;
  const auto limit = [&](double bound, const char* reason) {
    if (bound > 0.0 && bound < raw) {
      raw = bound;
      choice.limited_by = reason;
    }
  };
  if (magnify_gaps)
    for (std::size_t s = 0; s < model.struts.size() && s < widening.size(); ++s) {
      const solver::StrutMesh& mesh = model.struts[s];
      if (widening[s].empty()) continue;
      const double change = std::abs((widening[s].back() - widening[s].front()).dot(mesh.e1));
      if (change > 0.0) limit(1.0 + 0.25 * mesh.length / change, "gaps");
    }
  if (extent.largest_stretch > 0.0) limit(0.25 / extent.largest_stretch, "elements");
  for (std::size_t s = 0; s < extent.strut_lateral.size() && s < clearance.size(); ++s)
    if (extent.strut_lateral[s] > 0.0 && std::isfinite(clearance[s]) && clearance[s] > 0.0)
      limit(0.4 * clearance[s] / extent.strut_lateral[s], "crossing");
  choice.magnification = round_magnification(raw);
  return choice;
}

float caption_band(float text_size) {
  return 1.6f * text_size;
}

float legend_band(float text_size) {
  return 4.4f * text_size;
}

Rect geometry_region(const Rect& scene_region, float text_size) {
  Rect r = scene_region;
  r.y0 += caption_band(text_size);
  r.y1 -= legend_band(text_size);
  if (r.y1 < r.y0 + 1.0f) r.y1 = r.y0 + 1.0f;
  return r;
}

SceneFraming frame_scene(const solver::Model& model, const View& view, const RunExtent& extent,
                         const Rect& region) {
  SceneFraming framing;
  framing.region = region;
  framing.text_size = text_size(view);
  framing.line_width = std::max(1.0f, framing.text_size / 15.0f);
  framing.widening = view.magnify_gaps ? gap_widening(model) : std::vector<std::vector<Vec2>>{};
  framing.clearance = side_clearances(model);
  if (view.magnification > 0.0) {
    framing.magnification = view.magnification;
  } else {
    const MagnificationChoice choice = automatic_magnification(model, extent, view.magnify_gaps,
                                                               framing.widening, framing.clearance);
    framing.magnification = choice.magnification;
    framing.limited_by = choice.limited_by;
  }
  framing.gaps_magnified =
      view.magnify_gaps && framing.magnification != 1.0 && !model.pairs.empty();
  framing.force_scale = extent.largest_force;
  framing.stress_scale = extent.largest_stress;
  framing.moment_scale = extent.largest_moment;
  for (std::size_t s = 0; s < model.struts.size(); ++s) {
    const Eigen::VectorXd& load = model.loads[s];
    const int dofs = model.struts[s].dofs_per_node;
    for (int n = 0; n + dofs <= load.size(); n += dofs)
      framing.load_scale = std::max(framing.load_scale, load.segment(n, dofs).norm());
  }

  // The reference geometry (clamped ends do not move), widened by the largest magnified
  // displacement and gap widening.
  Bounds bounds;
  double widest = 0.0;
  for (std::size_t s = 0; s < model.struts.size(); ++s) {
    for (const Vec2& p : model.struts[s].nodes)
      bounds.include(p);
    if (framing.gaps_magnified && s < framing.widening.size())
      for (const Vec2& q : framing.widening[s])
        widest = std::max(widest, q.norm());
  }
  if (!bounds.valid()) bounds.include(Vec2::Zero());
  const double reach = framing.magnification * extent.largest_displacement +
                       (framing.gaps_magnified ? (framing.magnification - 1.0) * widest : 0.0);
  bounds.low -= Vec2(reach, reach);
  bounds.high += Vec2(reach, reach);

  // Room for supports, load arrows and glyphs around the geometry, between the caption
  // and the legends.
  const Rect fit = geometry_region(region, framing.text_size);
  const float margin = 2.2f * framing.text_size;
  const double room_x = std::max(1.0f, fit.width() - 2 * margin);
  const double room_y = std::max(1.0f, fit.height() - 2 * margin);
  const Vec2 size = bounds.high - bounds.low;
  double scale = kInfinity;
  if (size.x() > 0.0) scale = std::min(scale, room_x / size.x());
  if (size.y() > 0.0) scale = std::min(scale, room_y / size.y());
  if (!std::isfinite(scale)) scale = 1.0;
  framing.pixels_per_unit = scale;
  framing.world_center = 0.5 * (bounds.low + bounds.high);
  framing.pixel_center = {0.5f * (fit.x0 + fit.x1), 0.5f * (fit.y0 + fit.y1)};

  double apart = kInfinity;  // smallest distance between the axes of struts side by side
  for (std::size_t s = 0; s < model.struts.size(); ++s)
    if (std::isfinite(framing.clearance[s]))
      apart = std::min(apart, framing.clearance[s] + model.struts[s].height);
  if (std::isfinite(apart) && apart > 0.0) framing.lane = static_cast<float>(apart * scale);
  framing.fixed_bar = view.bar_width > 0.0f;
  framing.widest_bar = std::clamp(std::min(region.width(), region.height()) / 100.0f, 3.0f,
                                  9.0f * framing.line_width);
  framing.bar_width = framing.fixed_bar
                          ? view.bar_width
                          : std::min(framing.widest_bar, std::max(2.0f, 0.5f * framing.lane));
  return framing;
}

SceneFraming zoomed(const SceneFraming& framing, float zoom, Point center) {
  SceneFraming out = framing;
  out.pixels_per_unit *= zoom;
  out.pixel_center = center;
  if (framing.lane < 1e8f) out.lane = framing.lane * zoom;
  if (!out.fixed_bar) out.bar_width = std::min(out.widest_bar, std::max(2.0f, 0.5f * out.lane));
  return out;
}

SceneFraming placed(const SceneFraming& framing, const View& view) {
  const auto zoom = static_cast<float>(view.zoom);
  Point center = framing.pixel_center;
  if (view.centered) {
    const Point at =
        zoomed(framing, zoom, framing.pixel_center).to_pixel(Vec2(view.center_x, view.center_y));
    const Point middle{0.5f * (framing.region.x0 + framing.region.x1),
                       0.5f * (framing.region.y0 + framing.region.y1)};
    center = {framing.pixel_center.x + (middle.x - at.x),
              framing.pixel_center.y + (middle.y - at.y)};
  }
  return zoomed(framing, zoom, center);
}

}  // namespace fetic::render
