#include "render/scene_mesh.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <numeric>
#include <tuple>

#include "render/colormap.hpp"
#include "render/frame_sequence.hpp"
#include "solver/element_results.hpp"

namespace fetic::render {
namespace {

using solver::Vec2;

constexpr Color kOutline{55, 55, 62, 255};
constexpr Color kMeshLine{55, 55, 62, 110};
// Straight pieces per beam element (frame model) along its Hermite curve.
constexpr int kBeamSamples = 8;

// Position of each piece among the pieces of its strut, ordered along the strut.
std::vector<int> piece_ranks(const solver::Snapshot& snapshot) {
  std::vector<int> order(snapshot.pieces.size());
  std::iota(order.begin(), order.end(), 0);
  const auto key = [&](int p) {
    const solver::Piece& piece = snapshot.pieces[static_cast<std::size_t>(p)];
    return std::make_tuple(piece.strut, piece.box.i0, piece.box.k0);
  };
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return key(a) < key(b); });
  std::vector<int> rank(snapshot.pieces.size(), 0);
  for (std::size_t j = 1; j < order.size(); ++j) {
    const int previous = order[j - 1], current = order[j];
    rank[static_cast<std::size_t>(current)] =
        snapshot.pieces[static_cast<std::size_t>(previous)].strut ==
                snapshot.pieces[static_cast<std::size_t>(current)].strut
            ? rank[static_cast<std::size_t>(previous)] + 1
            : 0;
  }
  return rank;
}

bool same_box(const solver::NodeBox& a, const solver::NodeBox& b) {
  return a.i0 == b.i0 && a.i1 == b.i1 && a.k0 == b.k0 && a.k1 == b.k1;
}

// Appends the six vertices of a quad from corner vertices a b c d (in order around it).
void quad(std::vector<MeshVertex>& out, const MeshVertex& a, const MeshVertex& b,
          const MeshVertex& c, const MeshVertex& d) {
  out.insert(out.end(), {a, b, c, a, c, d});
}

// A band along the segment from node row a to node row b: `half` across (x: half bar
// widths, y: rim units, w: line widths), `inset_start` / `inset_end` along (rim units).
void band(std::vector<MeshVertex>& out, int a, int b, std::array<float, 3> half, float inset_start,
          float inset_end, int element, Color color, float t0 = 0.0f, float t1 = 1.0f) {
  const auto vertex = [&](float t, float side, float along) {
    MeshVertex v;
    v.node_a = a;
    v.node_b = b;
    v.t = t;
    v.offset = {side * half[0], side * half[1], along, side * half[2]};
    v.element = element;
    v.color = color;
    return v;
  };
  quad(out, vertex(t0, 1, inset_start), vertex(t1, 1, -inset_end), vertex(t1, -1, -inset_end),
       vertex(t0, -1, inset_start));
}

MeshVertex at_node(int row, int element, Color color) {
  MeshVertex v;
  v.node_a = v.node_b = row;
  v.element = element;
  v.color = color;
  return v;
}

std::atomic<std::uint64_t> next_id{1};

// The middle of the reference geometry (the mesh's origin).
Vec2 middle(const solver::Model& model) {
  Vec2 low = Vec2::Constant(std::numeric_limits<double>::infinity()), high = -low;
  for (const solver::StrutMesh& strut : model.struts)
    for (const Vec2& p : strut.nodes) {
      low = low.cwiseMin(p);
      high = high.cwiseMax(p);
    }
  return low.allFinite() && high.allFinite() ? Vec2(0.5 * (low + high)) : Vec2(0, 0);
}

// Where a plane piece's triangles go.
struct PlaneParts {
  std::vector<MeshVertex>&fills, &lines, &outlines;
};

// Appends a plane piece of na x nb kept nodes from node row `first` on: its cells (element
// rows from `element` on; -1 when `valueless`), inner lines when `lines`, and outline.
// Returns the next element row.
int plane_piece(PlaneParts out, int first, int na, int nb, int element, bool lines, Color fill,
                bool valueless) {
  // Kept node (a, b) is row at(a, b); a cell spans kept nodes a..a+1, b..b+1 (one element
  // unless merged).
  const auto at = [&](int a, int b) { return first + a * nb + b; };
  for (int a = 0; a + 1 < na; ++a)
    for (int b = 0; b + 1 < nb; ++b, ++element) {
      const int row = valueless ? -1 : element;
      quad(out.fills, at_node(at(a, b), row, fill), at_node(at(a + 1, b), row, fill),
           at_node(at(a + 1, b + 1), row, fill), at_node(at(a, b + 1), row, fill));
    }
  // Lines across (fixed i) and along (fixed k); the box's outer ones outline the piece.
  for (int a = 0; a < na; ++a) {
    const bool rim = a == 0 || a + 1 == na;
    if (!rim && !lines) continue;
    for (int b = 0; b + 1 < nb; ++b)
      band(rim ? out.outlines : out.lines, at(a, b), at(a, b + 1), {0, 0, rim ? 0.8f : 0.5f}, 0, 0,
           -1, rim ? kOutline : kMeshLine);
  }
  for (int b = 0; b < nb; ++b) {
    const bool rim = b == 0 || b + 1 == nb;
    if (!rim && !lines) continue;
    for (int a = 0; a + 1 < na; ++a)
      band(rim ? out.outlines : out.lines, at(a, b), at(a + 1, b), {0, 0, rim ? 0.8f : 0.5f}, 0, 0,
           -1, rim ? kOutline : kMeshLine);
  }
  return element;
}

// Inner mesh lines are drawn where the elements are at least this many pixels.
constexpr double kLinePixels = 6.0;

// World length of the shorter side of a plane strut's elements.
double element_side(const solver::StrutMesh& strut) {
  return std::min(strut.length / strut.nx,
                  strut.ny > 0 ? strut.height / strut.ny : strut.length / strut.nx);
}

// Elements merged per cell of a piece, along and across: 1, 1 except for plane pieces
// drawn at a level of detail; one cell for a piece outside the part kept in detail.
std::array<int, 2> merge_for(const solver::StrutMesh& strut, const solver::NodeBox& box,
                             const MeshDetail& detail) {
  if (strut.dofs_per_node != 2 || !(detail.pixels_per_unit > 0.0)) return {1, 1};
  const int along = box.i1 - box.i0, across = box.k1 - box.k0;
  WorldRect piece;
  piece.low = piece.high = strut.nodes[static_cast<std::size_t>(strut.node(box.i0, box.k0))];
  for (const auto& [i, k] :
       {std::pair{box.i1, box.k0}, std::pair{box.i1, box.k1}, std::pair{box.i0, box.k1}}) {
    const Vec2& corner = strut.nodes[static_cast<std::size_t>(strut.node(i, k))];
    piece.low = piece.low.cwiseMin(corner);
    piece.high = piece.high.cwiseMax(corner);
  }
  if (!detail.keep.overlaps(piece)) return {std::max(along, 1), std::max(across, 1)};
  const double ppu = detail.pixels_per_unit;
  return {merge_stride(strut.length / strut.nx * ppu, along),
          merge_stride(strut.height / std::max(strut.ny, 1) * ppu, across)};
}

bool is_merged(const SceneMesh& mesh, std::size_t piece) {
  return piece < mesh.merged.size() && mesh.merged[piece] != std::array<int, 2>{1, 1};
}

// Per cell of a merged plane piece (in the order of its element rows), the mean of the
// values of the elements it holds (`values` per element, along the strut outer).
std::vector<double> cell_means(const solver::NodeBox& box, const std::array<int, 2>& merged,
                               const std::vector<double>& values) {
  const std::vector<int> kept_i = kept_nodes(box.i0, box.i1, merged[0]),
                         kept_k = kept_nodes(box.k0, box.k1, merged[1]);
  const int across = box.k1 - box.k0;
  std::vector<double> means;
  means.reserve((kept_i.size() - 1) * (kept_k.size() - 1));
  for (std::size_t a = 0; a + 1 < kept_i.size(); ++a)
    for (std::size_t b = 0; b + 1 < kept_k.size(); ++b) {
      double sum = 0.0;
      int count = 0;
      for (int i = kept_i[a]; i < kept_i[a + 1]; ++i)
        for (int k = kept_k[b]; k < kept_k[b + 1]; ++k) {
          const auto e = static_cast<std::size_t>((i - box.i0) * across + (k - box.k0));
          if (e < values.size() && std::isfinite(values[e])) {
            sum += values[e];
            ++count;
          }
        }
      means.push_back(count > 0 ? sum / count : 0.0);
    }
  return means;
}

}  // namespace

bool SceneMesh::fits(const solver::Snapshot& snapshot) const {
  if (snapshot.pieces.size() != layout.size()) return false;
  for (std::size_t p = 0; p < layout.size(); ++p)
    if (snapshot.pieces[p].strut != layout[p].first ||
        !same_box(snapshot.pieces[p].box, layout[p].second))
      return false;
  return true;
}

SceneMesh build_scene_mesh(const solver::Model& model, const solver::Snapshot& snapshot,
                           const SceneFraming& framing, ColorBy color_by,
                           const MeshDetail& detail) {
  SceneMesh mesh;
  mesh.detail = detail;
  mesh.id = next_id++;
  mesh.color_by = color_by;
  mesh.origin = middle(model);
  mesh.smallest_element = std::numeric_limits<double>::infinity();

  const auto ranks = piece_ranks(snapshot);
  std::vector<MeshVertex> rims, bar_fills, plane_fills, plane_lines, outlines;
  for (std::size_t p = 0; p < snapshot.pieces.size(); ++p) {
    const solver::Piece& piece = snapshot.pieces[p];
    const auto s = static_cast<std::size_t>(piece.strut);
    const solver::StrutMesh& strut = model.struts[s];
    const solver::NodeBox& box = piece.box;
    mesh.layout.emplace_back(piece.strut, box);
    const int first = static_cast<int>(mesh.nodes.size());
    mesh.first_node.push_back(first);
    mesh.first_element.push_back(mesh.element_count);
    // A plane piece at a level of detail keeps every merged-th node along and across.
    const std::array<int, 2> merged = merge_for(strut, box, detail);
    mesh.merged.push_back(merged);
    const std::vector<int> kept_i = kept_nodes(box.i0, box.i1, merged[0]),
                           kept_k = kept_nodes(box.k0, box.k1, merged[1]);
    for (int i : kept_i)
      for (int k : kept_k) {
        const auto node = static_cast<std::size_t>(strut.node(i, k));
        const Vec2 x = strut.nodes[node] - mesh.origin;
        const Vec2 q = framing.widening.empty() ? Vec2::Zero() : framing.widening[s][node];
        mesh.nodes.push_back({static_cast<float>(x.x()), static_cast<float>(x.y()),
                              static_cast<float>(q.x()), static_cast<float>(q.y())});
      }
    const auto row = [&](int i, int k) { return first + box.local(i, k); };
    // Struts without a value for the colouring (no moment in bars and planes) are grey and
    // take no element rows' colours.
    const bool valueless = color_by == ColorBy::Moment && strut.dofs_per_node != 3;
    const Color fill =
        valueless ? palette::no_value
                  : subdomain_color(piece.strut, color_by == ColorBy::Strut ? 0 : ranks[p]);
    const auto element_row = [&](int element) { return valueless ? -1 : element; };
    if (strut.dofs_per_node == 1) {
      const int elements = box.i1 - box.i0;
      if (elements <= 0) continue;
      band(rims, row(box.i0, 0), row(box.i1, 0), {1, 0, 0}, 0, 0, -1, kOutline);
      for (int e = 0; e < elements; ++e)
        band(bar_fills, row(box.i0 + e, 0), row(box.i0 + e + 1, 0), {1, -1, 0},
             e == 0 ? 1.0f : 0.0f, e + 1 == elements ? 1.0f : 0.0f,
             element_row(mesh.element_count + e), fill);
      mesh.element_count += elements;
      continue;
    }
    if (strut.dofs_per_node == 3) {
      // A beam: each element a band along its Hermite curve, kBeamSamples straight pieces
      // (the shader bends them with the node rotations), rims first, fills over them.
      const int elements = box.i1 - box.i0;
      if (elements <= 0) continue;
      for (int e = 0; e < elements; ++e)
        for (int j = 0; j < kBeamSamples; ++j) {
          const float t0 = static_cast<float>(j) / kBeamSamples;
          const float t1 = static_cast<float>(j + 1) / kBeamSamples;
          const bool first_piece = e == 0 && j == 0,
                     last_piece = e + 1 == elements && j + 1 == kBeamSamples;
          const int a = row(box.i0 + e, 0), b = row(box.i0 + e + 1, 0);
          band(rims, a, b, {1, 0, 0}, 0, 0, -1, kOutline, t0, t1);
          band(bar_fills, a, b, {1, -1, 0}, first_piece ? 1.0f : 0.0f, last_piece ? 1.0f : 0.0f,
               mesh.element_count + e, fill, t0, t1);
        }
      mesh.element_count += elements;
      continue;
    }
    mesh.smallest_element = std::min(mesh.smallest_element, element_side(strut));
    // Inner lines only where the elements are whole and can grow large enough on screen
    // within the level (mesh_uniforms draws them from 6 pixels).
    const bool lines = merged == std::array<int, 2>{1, 1} &&
                       (!(detail.pixels_per_unit > 0.0) ||
                        2.0 * element_side(strut) * detail.pixels_per_unit >= kLinePixels);
    mesh.element_count =
        plane_piece({plane_fills, plane_lines, outlines}, first, static_cast<int>(kept_i.size()),
                    static_cast<int>(kept_k.size()), mesh.element_count, lines, fill, valueless);
  }
  if (!std::isfinite(mesh.smallest_element)) mesh.smallest_element = 0.0;
  const auto append = [&](std::vector<MeshVertex>& part, MeshRange& range) {
    range.first = static_cast<std::int32_t>(mesh.vertices.size());
    range.count = static_cast<std::int32_t>(part.size());
    mesh.vertices.insert(mesh.vertices.end(), part.begin(), part.end());
    part.clear();
    part.shrink_to_fit();
  };
  append(rims, mesh.bar_rims);
  append(bar_fills, mesh.bar_fills);
  append(plane_fills, mesh.plane_fills);
  append(plane_lines, mesh.plane_lines);
  append(outlines, mesh.plane_outlines);
  return mesh;
}

void fill_mesh_values(const SceneMesh& mesh, const solver::Model& model,
                      const solver::Snapshot& snapshot, const SceneFraming& framing,
                      MeshValues& values) {
  values.nodes.resize(mesh.nodes.size());
  for (std::size_t p = 0; p < snapshot.pieces.size() && p < mesh.first_node.size(); ++p) {
    const solver::Piece& piece = snapshot.pieces[p];
    auto* out = values.nodes.data() + mesh.first_node[p];
    const auto value = [&](std::size_t l) {
      const Vec2& u = piece.displacement[l];
      const double rotation = l < piece.rotation.size() ? piece.rotation[l] : 0.0;
      return u.allFinite() && std::isfinite(rotation)
                 ? std::array<float, 4>{static_cast<float>(u.x()), static_cast<float>(u.y()),
                                        static_cast<float>(rotation), 0.0f}
                 : std::array<float, 4>{0, 0, 0, 0};
    };
    if (is_merged(mesh, p)) {
      const solver::NodeBox& box = piece.box;
      std::size_t row = 0;
      for (int i : kept_nodes(box.i0, box.i1, mesh.merged[p][0]))
        for (int k : kept_nodes(box.k0, box.k1, mesh.merged[p][1]))
          out[row++] = value(static_cast<std::size_t>(box.local(i, k)));
      continue;
    }
    for (std::size_t l = 0; l < piece.displacement.size(); ++l)
      out[l] = value(l);
  }
  values.elements.assign(static_cast<std::size_t>(mesh.element_count), {0.0f, 0.0f});
  const auto scaled = [](double value, double scale) {
    const double v = value / scale;
    return std::isfinite(v) ? static_cast<float>(v) : 0.0f;
  };
  if (mesh.color_by == ColorBy::Stress && framing.stress_scale > 0.0) {
    const auto stresses = piece_stresses(model, snapshot);
    for (std::size_t p = 0; p < stresses.size() && p < mesh.first_element.size(); ++p) {
      auto* out = values.elements.data() + mesh.first_element[p];
      if (is_merged(mesh, p)) {
        const auto means = cell_means(snapshot.pieces[p].box, mesh.merged[p], stresses[p]);
        for (std::size_t c = 0; c < means.size(); ++c) {
          const float v = scaled(means[c], framing.stress_scale);
          out[c] = {v, v};
        }
        continue;
      }
      for (std::size_t e = 0; e < stresses[p].size(); ++e) {
        const float v = scaled(stresses[p][e], framing.stress_scale);
        out[e] = {v, v};
      }
    }
  } else if (mesh.color_by == ColorBy::Moment && framing.moment_scale > 0.0) {
    const auto moments = solver::piece_moments(model, snapshot);
    for (std::size_t p = 0; p < moments.size() && p < mesh.first_element.size(); ++p)
      for (std::size_t e = 0; e < moments[p].ends.size(); ++e)
        values.elements[static_cast<std::size_t>(mesh.first_element[p]) + e] = {
            scaled(moments[p].ends[e][0], framing.moment_scale),
            scaled(moments[p].ends[e][1], framing.moment_scale)};
  }
}

MeshUniforms mesh_uniforms(const SceneMesh& mesh, const SceneFraming& framing) {
  MeshUniforms u;
  u.magnification = static_cast<float>(framing.magnification);
  u.widening = framing.gaps_magnified ? static_cast<float>(framing.magnification - 1.0) : 0.0f;
  const Vec2 center = framing.world_center - mesh.origin;
  u.center = {static_cast<float>(center.x()), static_cast<float>(center.y())};
  u.pixel_center = {framing.pixel_center.x, framing.pixel_center.y};
  u.pixels_per_unit = static_cast<float>(framing.pixels_per_unit);
  u.half_bar_width = 0.5f * framing.bar_width;
  u.rim = framing.bar_width >= 4.0f ? 1.0f : 0.0f;
  u.line_width = framing.line_width;
  u.by_value = colors_by_value(mesh.color_by);
  // Mesh lines only where elements are large enough on screen not to fill with them.
  u.mesh_lines = mesh.smallest_element * framing.pixels_per_unit >= 6.0;
  return u;
}

void expand_mesh(const SceneMesh& mesh, const MeshValues& values, const MeshUniforms& u,
                 DrawList& out) {
  const auto world = [&](int row) {
    const auto& r = mesh.nodes[static_cast<std::size_t>(row)];
    const auto& v = values.nodes[static_cast<std::size_t>(row)];
    return std::array<float, 2>{r[0] + u.widening * r[2] + u.magnification * v[0],
                                r[1] + u.widening * r[3] + u.magnification * v[1]};
  };
  const auto screen = [&](const std::array<float, 2>& w) {
    return Point{u.pixel_center[0] + (w[0] - u.center[0]) * u.pixels_per_unit,
                 u.pixel_center[1] - (w[1] - u.center[1]) * u.pixels_per_unit};
  };
  // What the Hermite shape of a beam element adds to the straight line between its nodes
  // at t (world, magnified); zero at t = 0 and 1, so bars and planes are unchanged.
  const auto bending = [&](const MeshVertex& v) {
    const auto& ra = mesh.nodes[static_cast<std::size_t>(v.node_a)];
    const auto& rb = mesh.nodes[static_cast<std::size_t>(v.node_b)];
    const auto& va = values.nodes[static_cast<std::size_t>(v.node_a)];
    const auto& vb = values.nodes[static_cast<std::size_t>(v.node_b)];
    const float ex = rb[0] - ra[0], ey = rb[1] - ra[1];
    const float h = std::sqrt(ex * ex + ey * ey);
    if (!(h > 0.0f)) return std::array<float, 2>{0, 0};
    const float nx = -ey / h, ny = ex / h;  // e2
    const float t = v.t;
    const float wa = va[0] * nx + va[1] * ny, wb = vb[0] * nx + vb[1] * ny;
    const float c = (1 - 3 * t * t + 2 * t * t * t - (1 - t)) * wa +
                    (3 * t * t - 2 * t * t * t - t) * wb +
                    h * ((t - 2 * t * t + t * t * t) * va[2] + (t * t * t - t * t) * vb[2]);
    return std::array<float, 2>{u.magnification * c * nx, u.magnification * c * ny};
  };
  const auto place = [&](const MeshVertex& v) {
    const Point a = screen(world(v.node_a)), b = screen(world(v.node_b));
    Point d = normalized(b - a);
    if (d == Point{}) d = {1.0f, 0.0f};
    const Point n = perpendicular(d);
    const float across =
        v.offset[0] * u.half_bar_width + v.offset[1] * u.rim + v.offset[3] * u.line_width;
    const float along = v.offset[2] * u.rim;
    Color color = v.color;
    if (v.element >= 0 && u.by_value) {
      const auto& ends = values.elements[static_cast<std::size_t>(v.element)];
      color = diverging((1.0f - v.t) * ends[0] + v.t * ends[1]);
    }
    const auto bend = bending(v);
    const Point curve{bend[0] * u.pixels_per_unit, -bend[1] * u.pixels_per_unit};
    return Vertex{a + v.t * (b - a) + curve + across * n + along * d, color};
  };
  const auto draw = [&](const MeshRange& range) {
    for (std::int32_t i = range.first; i + 2 < range.first + range.count; i += 3)
      out.triangle(place(mesh.vertices[static_cast<std::size_t>(i)]),
                   place(mesh.vertices[static_cast<std::size_t>(i + 1)]),
                   place(mesh.vertices[static_cast<std::size_t>(i + 2)]));
  };
  if (u.rim > 0.0f) draw(mesh.bar_rims);
  draw(mesh.bar_fills);
  draw(mesh.plane_fills);
  if (u.mesh_lines) draw(mesh.plane_lines);
  draw(mesh.plane_outlines);
}

}  // namespace fetic::render
