#include "render/scene_drawing.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "render/colormap.hpp"
#include "render/text_format.hpp"
#include "scenes/units.hpp"

namespace fetic::render {
namespace {

using solver::Vec2;

struct NodeRef {
  int piece = -1;
  int local = -1;
};

// For every strut node, the first piece that holds it (a FETI interface node is held by
// several; contacts and loads are drawn where the first of them puts it).
std::vector<std::vector<NodeRef>> node_refs(const solver::Model& model,
                                            const solver::Snapshot& snapshot) {
  std::vector<std::vector<NodeRef>> refs(model.struts.size());
  for (std::size_t s = 0; s < model.struts.size(); ++s)
    refs[s].resize(static_cast<std::size_t>(model.struts[s].node_count()));
  for (std::size_t p = 0; p < snapshot.pieces.size(); ++p) {
    const solver::Piece& piece = snapshot.pieces[p];
    const solver::StrutMesh& mesh = model.struts[static_cast<std::size_t>(piece.strut)];
    for (int i = piece.box.i0; i <= piece.box.i1; ++i)
      for (int k = piece.box.k0; k <= piece.box.k1; ++k) {
        NodeRef& ref =
            refs[static_cast<std::size_t>(piece.strut)][static_cast<std::size_t>(mesh.node(i, k))];
        if (ref.piece < 0) ref = {static_cast<int>(p), piece.box.local(i, k)};
      }
  }
  return refs;
}

Vec2 displacement_of(const std::vector<std::vector<NodeRef>>& refs,
                     const solver::Snapshot& snapshot, int strut, int node) {
  const NodeRef& ref = refs[static_cast<std::size_t>(strut)][static_cast<std::size_t>(node)];
  if (ref.piece < 0) return Vec2::Zero();
  const Vec2& u = snapshot.pieces[static_cast<std::size_t>(ref.piece)]
                      .displacement[static_cast<std::size_t>(ref.local)];
  return u.allFinite() ? u : Vec2::Zero();
}

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

Vec2 piece_u(const solver::Piece& piece, int local) {
  const Vec2& u = piece.displacement[static_cast<std::size_t>(local)];
  return u.allFinite() ? u : Vec2::Zero();
}

constexpr Color kOutline{55, 55, 62, 255};

// A bar piece: a band of the fixed on-screen width along its drawn nodes, a dark rim and
// per-element fill colours.
void draw_bar_piece(DrawList& list, const std::vector<Point>& nodes, Point axis, float width,
                    const std::vector<Color>& fills) {
  const Point side = perpendicular(axis);
  const auto band = [&](Point a, Point b, float half, Color color) {
    list.quad(a + half * side, b + half * side, b - half * side, a - half * side, color);
  };
  const std::size_t elements = nodes.size() - 1;
  if (width < 4.0f) {
    for (std::size_t e = 0; e < elements; ++e)
      band(nodes[e], nodes[e + 1], width / 2, fills[e]);
    return;
  }
  band(nodes.front(), nodes.back(), width / 2, kOutline);
  for (std::size_t e = 0; e < elements; ++e) {
    Point a = nodes[e], b = nodes[e + 1];
    if (e == 0) a = a + 1.0f * axis;  // inset the fill at the ends of the piece
    if (e + 1 == elements) b = b - 1.0f * axis;
    band(a, b, width / 2 - 1.0f, fills[e]);
  }
}

void draw_plane_piece(DrawList& list, const solver::Piece& piece, const std::vector<Point>& nodes,
                      const std::vector<Color>& fills) {
  const solver::NodeBox& box = piece.box;
  const auto at = [&](int i, int k) { return nodes[static_cast<std::size_t>(box.local(i, k))]; };
  int element = 0;
  for (int i = box.i0; i < box.i1; ++i)
    for (int k = box.k0; k < box.k1; ++k, ++element)
      list.quad(at(i, k), at(i + 1, k), at(i + 1, k + 1), at(i, k + 1),
                fills[static_cast<std::size_t>(element)]);
  const Color mesh_line = with_alpha(kOutline, 110);
  for (int i = box.i0; i <= box.i1; ++i) {
    std::vector<Point> line;
    for (int k = box.k0; k <= box.k1; ++k)
      line.push_back(at(i, k));
    const bool rim = i == box.i0 || i == box.i1;
    list.polyline(line, rim ? 1.6f : 1.0f, rim ? kOutline : mesh_line);
  }
  for (int k = box.k0; k <= box.k1; ++k) {
    std::vector<Point> line;
    for (int i = box.i0; i <= box.i1; ++i)
      line.push_back(at(i, k));
    const bool rim = k == box.k0 || k == box.k1;
    list.polyline(line, rim ? 1.6f : 1.0f, rim ? kOutline : mesh_line);
  }
}

// A wall across `outward` at `at`, hatched on the outside.
void draw_support(DrawList& list, Point at, Point outward, float half_length, float text_size) {
  const Point along = perpendicular(outward);
  const Point base = at + 1.5f * outward;
  const float hatch = std::max(5.0f, 0.45f * text_size);
  const float spacing = std::max(3.5f, 0.3f * text_size);
  list.line(base - half_length * along, base + half_length * along, 2.0f, palette::wall);
  for (float s = -half_length + spacing; s <= half_length + 0.01f; s += spacing) {
    const Point start = base + s * along;
    list.line(start, start + hatch * outward - hatch * along, 1.2f, palette::wall);
  }
}

void draw_supports(DrawList& list, const solver::Model& model, const SceneFraming& framing) {
  for (std::size_t s = 0; s < model.struts.size(); ++s) {
    const solver::StrutMesh& mesh = model.struts[s];
    const auto& clamped = model.clamped_nodes[s];
    const Point axis = framing.direction(mesh.e1);
    const float half = mesh.dofs_per_node == 1
                           ? 1.6f * framing.bar_width + 2.0f
                           : static_cast<float>(0.5 * mesh.height * framing.pixels_per_unit) + 4.0f;
    const Vec2 offset = framing.strut_offset[s];
    if (std::binary_search(clamped.begin(), clamped.end(), mesh.node(0, 0)))
      draw_support(list, framing.to_pixel(mesh.origin + offset), -1.0f * axis, half,
                   framing.text_size);
    if (std::binary_search(clamped.begin(), clamped.end(), mesh.node(mesh.nx, 0)))
      draw_support(list, framing.to_pixel(mesh.origin + mesh.length * mesh.e1 + offset), axis, half,
                   framing.text_size);
  }
}

void draw_loads(DrawList& list, const solver::Model& model, const solver::Snapshot& snapshot,
                const std::vector<std::vector<NodeRef>>& refs, const SceneFraming& framing) {
  if (!(framing.load_scale > 0.0)) return;
  const float text = framing.text_size;
  for (std::size_t s = 0; s < model.struts.size(); ++s) {
    const solver::StrutMesh& mesh = model.struts[s];
    const Eigen::VectorXd& load = model.loads[s];
    const int dofs = mesh.dofs_per_node;
    Point side = perpendicular(framing.direction(mesh.e1));
    if (side.y > 0.0f || (side.y == 0.0f && side.x > 0.0f)) side = -1.0f * side;  // above
    for (int n = 0; n < mesh.node_count(); ++n) {
      const Vec2 force = dofs == 1 ? Vec2(load[n] * mesh.e1) : Vec2(load[2 * n], load[2 * n + 1]);
      const double magnitude = std::abs(snapshot.load_factor) * force.norm();
      if (!(magnitude > 1e-12 * framing.load_scale)) continue;
      const Point direction = framing.direction(snapshot.load_factor * force);
      const float arrow =
          (1.0f + 1.6f * static_cast<float>(std::min(1.0, magnitude / framing.load_scale))) * text;
      const Point node = framing.node(model, static_cast<int>(s), n,
                                      displacement_of(refs, snapshot, static_cast<int>(s), n));
      // The head touches the point of application; a bar's interior loads sit beside it.
      const int i = n / mesh.nodes_across();
      const bool beside = dofs == 1 && i != 0 && i != mesh.nx;
      const Point tip = beside ? node + (0.5f * framing.bar_width + 3.0f) * side : node;
      const Point tail = tip - arrow * direction;
      list.arrow(tail, tip, std::max(1.6f, text / 8.0f), std::min(0.45f * arrow, 0.7f * text),
                 palette::load);
    }
  }
}

void draw_stress_legend(DrawList& list, const SceneFraming& framing, const scenes::Units& units) {
  const float text = framing.text_size;
  const Rect& region = framing.region;
  const float width = std::min(13.0f * text, 0.4f * region.width());
  const float height = 0.7f * text;
  const float x0 = region.x0 + 2.2f * text, y1 = region.y1 - 1.4f * text;
  const float y0 = y1 - height;
  constexpr int kSteps = 48;
  for (int j = 0; j < kSteps; ++j) {
    const float xa = x0 + width * j / kSteps, xb = x0 + width * (j + 1) / kSteps;
    const Color ca = diverging(-1.0 + 2.0 * j / kSteps);
    const Color cb = diverging(-1.0 + 2.0 * (j + 1) / kSteps);
    list.triangle({{xa, y0}, ca}, {{xb, y0}, cb}, {{xb, y1}, cb});
    list.triangle({{xa, y0}, ca}, {{xb, y1}, cb}, {{xa, y1}, ca});
  }
  list.rect_outline({x0, y0, x0 + width, y1}, 1.0f, kOutline);
  const double scale = framing.stress_scale;
  const scenes::DisplayUnit display = scenes::display_unit(scenes::Quantity::Stress, units, scale);
  const std::string& unit = display.name;
  const double divisor = display.divisor;
  const float label = 0.85f * text;
  const std::vector<std::pair<float, double>> ticks{{0.0f, -scale}, {0.5f, 0.0}, {1.0f, scale}};
  for (const auto& [where, value] : ticks) {
    const float x = x0 + where * width;
    list.line({x, y1}, {x, y1 + 0.3f * text}, 1.0f, kOutline);
    list.text(value == 0.0 ? std::string("0") : format("%.3g", value / divisor),
              {x, y1 + 0.35f * text}, label, palette::ink, HAlign::Center, VAlign::Top);
  }
  list.text("axial stress [" + unit + "]  compression - tension", {x0, y0 - 0.25f * text}, label,
            palette::ink, HAlign::Left, VAlign::Bottom);
}

}  // namespace

std::vector<ContactMark> contact_marks(const solver::Model& model, const solver::Snapshot& snapshot,
                                       const SceneFraming& framing) {
  const auto refs = node_refs(model, snapshot);
  std::vector<ContactMark> marks;
  marks.reserve(model.pairs.size());
  for (std::size_t p = 0; p < model.pairs.size(); ++p) {
    const solver::ContactPair& pair = model.pairs[p];
    ContactMark mark;
    mark.pair = static_cast<int>(p);
    mark.a = framing.node(model, pair.strut_a, pair.node_a,
                          displacement_of(refs, snapshot, pair.strut_a, pair.node_a));
    mark.b = framing.node(model, pair.strut_b, pair.node_b,
                          displacement_of(refs, snapshot, pair.strut_b, pair.node_b));
    mark.center = 0.5f * (mark.a + mark.b);
    mark.normal = framing.direction(pair.normal);
    mark.active = p < snapshot.in_working_set.size() && snapshot.in_working_set[p];
    mark.force =
        p < snapshot.force.size() && std::isfinite(snapshot.force[p]) ? snapshot.force[p] : 0.0;
    marks.push_back(mark);
  }
  return marks;
}

std::vector<std::vector<Point>> piece_outline_nodes(const solver::Model& model,
                                                    const solver::Snapshot& snapshot,
                                                    const SceneFraming& framing) {
  std::vector<std::vector<Point>> result;
  result.reserve(snapshot.pieces.size());
  for (const solver::Piece& piece : snapshot.pieces) {
    const solver::StrutMesh& mesh = model.struts[static_cast<std::size_t>(piece.strut)];
    std::vector<Point> nodes(static_cast<std::size_t>(piece.box.node_count()));
    for (int i = piece.box.i0; i <= piece.box.i1; ++i)
      for (int k = piece.box.k0; k <= piece.box.k1; ++k)
        nodes[static_cast<std::size_t>(piece.box.local(i, k))] = framing.node(
            model, piece.strut, mesh.node(i, k), piece_u(piece, piece.box.local(i, k)));
    result.push_back(std::move(nodes));
  }
  return result;
}

DrawList draw_scene(const solver::Model& model, const solver::Snapshot& snapshot, const View& view,
                    const SceneFraming& framing) {
  DrawList list;
  const auto refs = node_refs(model, snapshot);
  const auto marks = contact_marks(model, snapshot, framing);
  const float text = framing.text_size;

  if (view.show_gaps)
    for (const ContactMark& mark : marks)
      if (!mark.active && length(mark.b - mark.a) > 2.0f)
        list.dashed_line(mark.a, mark.b, 1.2f, 3.0f, 2.5f, palette::gap);
  if (view.show_supports) draw_supports(list, model, framing);

  const auto ranks = piece_ranks(snapshot);
  const auto nodes = piece_outline_nodes(model, snapshot, framing);
  const bool by_stress = view.color_by == ColorBy::Stress;
  const auto stresses =
      by_stress ? piece_stresses(model, snapshot) : std::vector<std::vector<double>>{};
  for (std::size_t p = 0; p < snapshot.pieces.size(); ++p) {
    const solver::Piece& piece = snapshot.pieces[p];
    const solver::StrutMesh& mesh = model.struts[static_cast<std::size_t>(piece.strut)];
    const int elements = mesh.dofs_per_node == 1
                             ? piece.box.i1 - piece.box.i0
                             : (piece.box.i1 - piece.box.i0) * (piece.box.k1 - piece.box.k0);
    if (elements <= 0) continue;
    std::vector<Color> fills(
        static_cast<std::size_t>(elements),
        subdomain_color(piece.strut, view.color_by == ColorBy::Strut ? 0 : ranks[p]));
    if (by_stress)
      for (int e = 0; e < elements; ++e)
        fills[static_cast<std::size_t>(e)] =
            diverging(framing.stress_scale > 0.0
                          ? stresses[p][static_cast<std::size_t>(e)] / framing.stress_scale
                          : 0.0);
    if (mesh.dofs_per_node == 1)
      draw_bar_piece(list, nodes[p], framing.direction(mesh.e1), framing.bar_width, fills);
    else
      draw_plane_piece(list, piece, nodes[p], fills);
  }

  if (view.show_loads) draw_loads(list, model, snapshot, refs, framing);
  // Active contacts: red circles, as in the thesis; the contact force as a disc inside
  // whose area is proportional to lambda.
  const float radius =
      std::clamp(0.45f * framing.lane, 4.0f, std::max(4.0f, 1.2f * framing.bar_width + 3.0f));
  if (view.show_forces && framing.force_scale > 0.0)
    for (const ContactMark& mark : marks)
      if (mark.force > 0.0)
        list.disc(mark.center,
                  std::max(1.5f, 0.8f * radius *
                                     static_cast<float>(std::sqrt(
                                         std::min(1.0, mark.force / framing.force_scale)))),
                  palette::force);
  if (view.show_contacts)
    for (const ContactMark& mark : marks)
      if (mark.active)
        list.ring(mark.center, radius, std::max(1.5f, text / 10.0f), palette::contact);

  if (by_stress) draw_stress_legend(list, framing, model.units);
  const std::string what = framing.gaps_magnified ? "displacements and gaps " : "displacements ";
  list.text(what + times(framing.magnification),
            {framing.region.x1 - text, framing.region.y1 - 0.6f * text}, 0.9f * text,
            palette::muted, HAlign::Right, VAlign::Bottom);
  return list;
}

}  // namespace fetic::render
