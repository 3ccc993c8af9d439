#include "render/scene_drawing.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <numeric>

#include "render/colormap.hpp"
#include "render/frame_sequence.hpp"
#include "render/text_format.hpp"
#include "scenes/units.hpp"
#include "solver/element_results.hpp"

namespace fetic::render {
namespace {

using solver::Vec2;

constexpr Color kOutline{55, 55, 62, 255};

// Finds the displacement of any strut node in a snapshot: the first piece that holds it
// (a FETI interface node is held by several; glyphs sit where the first puts it).
class NodeLookup {
 public:
  NodeLookup(const solver::Model& model, const solver::Snapshot& snapshot)
      : model_(model), snapshot_(snapshot), pieces_(model.struts.size()) {
    for (std::size_t p = 0; p < snapshot.pieces.size(); ++p) {
      const auto s = static_cast<std::size_t>(snapshot.pieces[p].strut);
      if (s < pieces_.size()) pieces_[s].push_back(p);
    }
  }
  Vec2 displacement(int strut, int node) const {
    const solver::StrutMesh& mesh = model_.struts[static_cast<std::size_t>(strut)];
    const int i = node / mesh.nodes_across(), k = node % mesh.nodes_across();
    for (std::size_t p : pieces_[static_cast<std::size_t>(strut)]) {
      const solver::Piece& piece = snapshot_.pieces[p];
      if (!piece.box.contains(i, k)) continue;
      const Vec2& u = piece.displacement[static_cast<std::size_t>(piece.box.local(i, k))];
      return u.allFinite() ? u : Vec2::Zero();
    }
    return Vec2::Zero();
  }

 private:
  const solver::Model& model_;
  const solver::Snapshot& snapshot_;
  std::vector<std::vector<std::size_t>> pieces_;
};

Vec2 piece_u(const solver::Piece& piece, int local) {
  const Vec2& u = piece.displacement[static_cast<std::size_t>(local)];
  return u.allFinite() ? u : Vec2::Zero();
}

// The side of a strut that faces up on screen (or left for vertical struts): labels and
// arrows beside a strut go there.
Point upper_side(const SceneFraming& framing, const solver::StrutMesh& mesh) {
  Point side = perpendicular(framing.direction(mesh.e1));
  if (side.y > 0.0f || (side.y == 0.0f && side.x > 0.0f)) side = -1.0f * side;
  return side;
}

// Half the drawn width of a strut across its axis, in pixels.
float half_width_px(const SceneFraming& framing, const solver::StrutMesh& mesh) {
  return mesh.dofs_per_node != 2 ? 0.5f * framing.bar_width  // bars and beams
                                 : static_cast<float>(0.5 * mesh.height * framing.pixels_per_unit);
}

// Free pixels beside a strut (to the next one, heights taken off); huge when alone.
float free_px(const SceneFraming& framing, const solver::Model& model, int strut) {
  const auto s = static_cast<std::size_t>(strut);
  if (s >= framing.clearance.size() || !std::isfinite(framing.clearance[s])) return 1e6f;
  const float free = static_cast<float>(framing.clearance[s] * framing.pixels_per_unit);
  // Bars are drawn wider than their (zero) height.
  return model.struts[s].dofs_per_node != 2 ? free - framing.bar_width : free;
}

float length_px(const SceneFraming& framing, const solver::StrutMesh& mesh) {
  return static_cast<float>(mesh.length * framing.pixels_per_unit);
}

// What the glyph legend lists: kinds present, and how many were left out at this zoom.
struct GlyphTally {
  bool walls = false, loads = false, distributed = false, rings = false, faces = false,
       forces = false, gaps = false;
  bool pins = false, rigid_joints = false, pinned_joints = false;  // frame model
  int loads_left_out = 0, contacts_left_out = 0, labels_left_out = 0;
  double largest_load = 0.0;         // point loads drawn, at this load factor
  double largest_distributed = 0.0;  // per length
  double largest_force_now = 0.0;    // the largest contact force of the state shown
};

// --- supports ---------------------------------------------------------------------------

struct Wall {
  Point outward, along;
  float level = 0.0f;            // position along `outward` (pixels)
  float from = 0.0f, to = 0.0f;  // extent along `along`
};

void draw_wall(DrawList& list, const Wall& wall, const SceneFraming& framing) {
  const float lw = framing.line_width;
  const float hatch = std::max(5.0f, 0.45f * framing.text_size);
  const float spacing = std::max(3.5f, 0.3f * framing.text_size);
  // The wall line stands clear of the strut ends (a pixel of air), the hatching outside.
  const Point base = (wall.level + 1.0f + lw) * wall.outward;
  const Point a = base + wall.from * wall.along, b = base + wall.to * wall.along;
  list.line(a, b, 2.0f * lw, palette::wall);
  for (float s = wall.from + spacing; s <= wall.to + 0.01f; s += spacing) {
    const Point start = base + s * wall.along + lw * wall.outward;
    list.line(start, start + hatch * wall.outward - hatch * wall.along, 1.2f * lw, palette::wall);
  }
}

// Frame model: a pinned support as a triangle on a hatched base, its tip on the node; a
// joint as a small filled square (rigid) or an open circle (pinned: the ends turn).
void draw_pins_and_joints(DrawList& list, const solver::Model& model, const SceneFraming& framing,
                          const NodeLookup& nodes, GlyphTally& tally) {
  const float lw = framing.line_width;
  const float size = std::max(8.0f * lw, 1.1f * framing.text_size);
  for (std::size_t s = 0; s < model.end_supports.size(); ++s) {
    const solver::StrutMesh& mesh = model.struts[s];
    for (int end = 0; end < 2; ++end) {
      if (model.end_supports[s][static_cast<std::size_t>(end)] != solver::Support::Pinned) continue;
      const int node = mesh.node(end == 0 ? 0 : mesh.nx, 0);
      const Point at = framing.node(model, static_cast<int>(s), node, Vec2::Zero());
      const float half = 0.55f * size;
      const Point left{at.x - half, at.y + size}, right{at.x + half, at.y + size};
      list.triangle(at, left, right, palette::background);
      list.polyline({at, left, right}, 1.6f * lw, palette::wall, true);
      const float base = at.y + size + 1.5f * lw;
      list.line({at.x - 1.3f * half, base}, {at.x + 1.3f * half, base}, 2.0f * lw, palette::wall);
      const float hatch = std::max(4.0f, 0.35f * size), spacing = std::max(3.5f, 0.3f * size);
      for (float x = at.x - 1.3f * half + spacing; x <= at.x + 1.3f * half + 0.01f; x += spacing)
        list.line({x, base + lw}, {x - hatch, base + lw + hatch}, 1.2f * lw, palette::wall);
      tally.pins = true;
    }
  }
  const float joint = std::max(6.0f * lw, framing.bar_width + 4.0f * lw);
  for (const solver::JointLink& link : model.joints) {
    if (link.ends.empty()) continue;
    const auto [strut, node] = link.ends.front();
    const Point at = framing.node(model, strut, node, nodes.displacement(strut, node));
    const float half = 0.5f * joint;
    if (link.shared == 3) {
      list.rect({at.x - half, at.y - half, at.x + half, at.y + half}, palette::wall);
      tally.rigid_joints = true;
    } else {
      list.disc(at, half, palette::background);
      list.ring(at, half, std::max(1.5f * lw, 0.25f * half), palette::wall);
      tally.pinned_joints = true;
    }
  }
}

// One wall per clamped end, merged where the ends of several struts line up (a column of
// clamped bars gets one straight wall, not a stack of short ones); then the frame model's
// pinned supports and joints.
void draw_supports(DrawList& list, const solver::Model& model, const SceneFraming& framing,
                   const NodeLookup& nodes, GlyphTally& tally) {
  std::map<std::tuple<int, int, long>, std::vector<std::pair<float, float>>> groups;
  std::map<std::tuple<int, int, long>, std::pair<Point, Point>> directions;
  for (std::size_t s = 0; s < model.struts.size(); ++s) {
    const solver::StrutMesh& mesh = model.struts[s];
    const auto& clamped = model.clamped_nodes[s];
    const Point axis = framing.direction(mesh.e1);
    const float half = half_width_px(framing, mesh) + 3.0f * framing.line_width;
    for (const bool at_to : {false, true}) {
      const int i = at_to ? mesh.nx : 0;
      if (!std::binary_search(clamped.begin(), clamped.end(), mesh.node(i, 0))) continue;
      const Point outward = at_to ? axis : -1.0f * axis;
      const Point along = perpendicular(outward);
      const Point end = framing.to_pixel(mesh.origin + (at_to ? mesh.length : 0.0) * mesh.e1);
      const float level = end.x * outward.x + end.y * outward.y;
      const float middle = end.x * along.x + end.y * along.y;
      // Group by direction (to a thousandth) and by level (to half a pixel).
      const auto key = std::make_tuple(static_cast<int>(std::lround(outward.x * 1000)),
                                       static_cast<int>(std::lround(outward.y * 1000)),
                                       std::lround(level * 2.0f));
      groups[key].push_back({middle - half, middle + half});
      directions[key] = {outward, along};
    }
  }
  draw_pins_and_joints(list, model, framing, nodes, tally);
  for (auto& [key, intervals] : groups) {
    std::sort(intervals.begin(), intervals.end());
    const auto [outward, along] = directions[key];
    const float level = static_cast<float>(std::get<2>(key)) / 2.0f;
    Wall wall{outward, along, level, intervals.front().first, intervals.front().second};
    for (std::size_t j = 1; j <= intervals.size(); ++j) {
      if (j < intervals.size() && intervals[j].first <= wall.to + 1.0f) {
        wall.to = std::max(wall.to, intervals[j].second);
        continue;
      }
      draw_wall(list, wall, framing);
      tally.walls = true;
      if (j < intervals.size()) {
        wall.from = intervals[j].first;
        wall.to = intervals[j].second;
      }
    }
  }
}

// --- loads ------------------------------------------------------------------------------

// An arrow of `length` pixels ending at `tip`, pointing along `direction`, whose head fits
// in `room` pixels across; false when even a small one does not fit.
bool fitted_arrow(DrawList& list, Point tip, Point direction, float length, float room,
                  const SceneFraming& framing, Color color) {
  const float lw = framing.line_width;
  float head = std::min(0.45f * length, 0.7f * framing.text_size);
  head = std::min(head, room);  // the head is as wide as it is long
  if (head < 3.0f * lw || length < 2.0f * head) return false;
  list.arrow(tip - length * direction, tip, std::max(1.4f * lw, framing.text_size / 9.0f), head,
             color);
  return true;
}

float arrow_length(const SceneFraming& framing, double magnitude, double scale) {
  const double share = scale > 0.0 ? std::min(1.0, magnitude / scale) : 1.0;
  return (1.0f + 1.6f * static_cast<float>(share)) * framing.text_size;
}

// A point load at a strut end: an arrow beside the strut whose head ends level with the
// point of application (an axial arrow along the strut would cover it), or, for a load
// across a plane strut, touching its side.
void draw_point_load(DrawList& list, const solver::Model& model, const SceneFraming& framing,
                     const NodeLookup& nodes, const scenes::Load& load, double factor,
                     GlyphTally& tally) {
  const solver::StrutMesh& mesh = model.struts[static_cast<std::size_t>(load.strut)];
  Vec2 force = factor * Vec2(load.force[0], load.force[1]);
  if (mesh.dofs_per_node == 1) force = force.dot(mesh.e1) * mesh.e1;  // only the axial part acts
  const double magnitude = force.norm();
  if (!(magnitude > 0.0)) return;
  tally.largest_load = std::max(tally.largest_load, magnitude);
  // A frame load may sit at any node of its strut.
  const auto face = load.node >= 0 ? std::vector<int>{load.node} : mesh.end_face(load.at);
  Vec2 center = Vec2::Zero();
  for (int node : face)
    center += framing.drawn(model, load.strut, node, nodes.displacement(load.strut, node));
  center /= static_cast<double>(face.size());
  const Point anchor = framing.to_pixel(center);
  const Point direction = framing.direction(force);
  const Point side = upper_side(framing, mesh);
  const float half = half_width_px(framing, mesh);
  const float room = free_px(framing, model, load.strut) - 2.0f * framing.line_width;
  const float length = std::min(arrow_length(framing, magnitude, framing.load_scale * factor),
                                0.45f * length_px(framing, mesh));
  const bool across = std::abs(force.normalized().dot(mesh.e2)) > 0.7;
  bool drawn = false;
  if (across && mesh.dofs_per_node == 2) {
    // Across a plane strut: the tip touches the side the force pushes on, from outside.
    const Point toward = direction.x * side.x + direction.y * side.y > 0 ? -1.0f * side : side;
    const Point tip = anchor + (half + framing.line_width) * toward;
    drawn = fitted_arrow(list, tip, direction, std::min(length, room), 0.8f * length, framing,
                         palette::load);
  } else {
    // Beside the strut, in the free lane on its upper side.
    const float head_room = room - 2.0f * framing.line_width;
    const float head = std::min({0.45f * length, 0.7f * framing.text_size, head_room});
    const Point tip = anchor + (half + framing.line_width + 0.5f * head) * side;
    drawn = head_room >= 3.0f * framing.line_width &&
            fitted_arrow(list, tip, direction, length, head, framing, palette::load);
  }
  if (drawn)
    tally.loads = true;
  else
    ++tally.loads_left_out;
}

// A distributed load: a row of small arrows along the strut on the side it comes from,
// tips at the strut's edge, tails on a common line (one glyph per strut side, however
// many nodes carry it).
void draw_distributed_load(DrawList& list, const solver::Model& model, const SceneFraming& framing,
                           const NodeLookup& nodes, const scenes::Load& load, double factor,
                           GlyphTally& tally) {
  const solver::StrutMesh& mesh = model.struts[static_cast<std::size_t>(load.strut)];
  Vec2 q = factor * Vec2(load.force[0], load.force[1]);
  if (mesh.dofs_per_node == 1) q = q.dot(mesh.e1) * mesh.e1;
  const double magnitude = q.norm();
  if (!(magnitude > 0.0)) return;
  tally.largest_distributed = std::max(tally.largest_distributed, magnitude);
  const Point direction = framing.direction(q);
  const Point side = upper_side(framing, mesh);
  // Transverse loads come from the side opposite to where they push; axial ones sit on
  // the upper side.
  const float push = direction.x * side.x + direction.y * side.y;
  const bool transverse = std::abs(q.normalized().dot(mesh.e2)) > 0.3;
  const Point from_side = transverse && push > 0.0f ? -1.0f * side : side;
  const float half = half_width_px(framing, mesh);
  const float room = free_px(framing, model, load.strut) - 2.0f * framing.line_width;
  const float length = transverse
                           ? std::min(1.3f * framing.text_size, 0.6f * room)
                           : std::min(1.6f * framing.text_size, 0.3f * length_px(framing, mesh));
  const int count =
      std::clamp(static_cast<int>(length_px(framing, mesh) / (2.5f * framing.text_size)), 2, 9);
  // Edge nodes along the side the arrows stand on.
  const int k =
      mesh.dofs_per_node == 1 ? 0
      : (from_side.x * framing.direction(mesh.e2).x + from_side.y * framing.direction(mesh.e2).y >
         0.0f)
          ? mesh.ny
          : 0;
  const float offset = mesh.dofs_per_node == 1 ? half + framing.line_width : framing.line_width;
  std::vector<Point> tips;
  for (int j = 0; j < count; ++j) {
    const double xi = (j + 0.5) / count;
    const double position = xi * mesh.nx;
    const int i = std::min(static_cast<int>(position), mesh.nx - 1);
    const double w = position - i;
    const int n0 = mesh.node(i, k), n1 = mesh.node(i + 1, k);
    const Vec2 p =
        (1.0 - w) * framing.drawn(model, load.strut, n0, nodes.displacement(load.strut, n0)) +
        w * framing.drawn(model, load.strut, n1, nodes.displacement(load.strut, n1));
    tips.push_back(framing.to_pixel(p) + offset * from_side);
  }
  bool drawn = true;
  if (transverse) {
    const float head = std::min(0.45f * length, 0.5f * framing.text_size);
    drawn = room >= 8.0f * framing.line_width && length >= 2.0f * head && head >= 3.0f;
    if (drawn) {
      for (const Point& tip : tips)
        list.arrow(tip - length * direction, tip, 1.2f * framing.line_width, head, palette::load);
      list.line(tips.front() - length * direction, tips.back() - length * direction,
                1.2f * framing.line_width, palette::load);
    }
  } else {
    const float head = std::min(0.5f * framing.text_size, room - framing.line_width);
    drawn = head >= 3.0f * framing.line_width;
    if (drawn) {
      const Point shift = (0.5f * head) * from_side;
      list.line(tips.front() + shift, tips.back() + shift, 1.2f * framing.line_width,
                palette::load);
      for (const Point& tip : tips)
        list.arrow(tip + shift - head * direction, tip + shift + 0.5f * head * direction,
                   1.2f * framing.line_width, head, palette::load);
    }
  }
  if (drawn)
    tally.distributed = true;
  else
    ++tally.loads_left_out;
}

// --- contacts and gaps ------------------------------------------------------------------

// Axis spacing (pixels) around a contact and the drawn length of its shorter strut.
std::pair<float, float> contact_room(const solver::Model& model, const SceneFraming& framing,
                                     const solver::ContactPair& pair) {
  const auto room = [&](int strut) {
    const auto s = static_cast<std::size_t>(strut);
    const float spacing = s < framing.clearance.size() && std::isfinite(framing.clearance[s])
                              ? static_cast<float>((framing.clearance[s] + model.struts[s].height) *
                                                   framing.pixels_per_unit)
                              : 1e6f;
    return std::pair{spacing, length_px(framing, model.struts[s])};
  };
  const auto [sa, la] = room(pair.strut_a);
  const auto [sb, lb] = room(pair.strut_b);
  return {std::min(sa, sb), std::min(la, lb)};
}

void draw_gaps_and_contacts(DrawList& list, const solver::Model& model,
                            const solver::Snapshot& snapshot, const View& view,
                            const SceneFraming& framing, GlyphTally& tally) {
  const auto marks = contact_marks(model, snapshot, framing);
  const float lw = framing.line_width;
  for (std::size_t c = 0; c + 1 < model.contact_first_pair.size(); ++c) {
    const int first = model.contact_first_pair[c], last = model.contact_first_pair[c + 1];
    if (first >= last) continue;
    const solver::ContactPair& pair = model.pairs[static_cast<std::size_t>(first)];
    const auto [spacing, shorter] = contact_room(model, framing, pair);
    const bool bar = model.struts[static_cast<std::size_t>(pair.strut_a)].dofs_per_node == 1;
    // Open gaps: a dashed line across the gap (for a face, at its middle pair), clear of
    // the strut ends by a pixel.
    if (view.show_gaps) {
      const ContactMark& middle = marks[static_cast<std::size_t>((first + last) / 2)];
      const float gap = length(middle.b - middle.a);
      if (!middle.active && gap >= 4.0f * lw) {
        const Point d = normalized(middle.b - middle.a);
        list.dashed_line(middle.a + lw * d, middle.b - lw * d, 1.2f * lw, 3.0f * lw, 2.5f * lw,
                         palette::gap);
        tally.gaps = true;
      }
    }
    if (!view.show_contacts && !view.show_forces) continue;
    bool any_active = false;
    for (int p = first; p < last; ++p)
      any_active = any_active || marks[static_cast<std::size_t>(p)].active ||
                   marks[static_cast<std::size_t>(p)].force > 0.0;
    if (!any_active) continue;
    const auto share = [&](double force) {
      return framing.force_scale > 0.0
                 ? static_cast<float>(std::sqrt(std::min(1.0, force / framing.force_scale)))
                 : 0.0f;
    };
    // Rings (the thesis' red circles) where a bar contact has room: the ring and the force
    // disc inside may cover at most a tenth of each strut's length.
    if (bar) {
      const ContactMark& mark = marks[static_cast<std::size_t>(first)];
      const float radius = std::min(0.45f * spacing, 1.2f * framing.bar_width + 3.0f * lw);
      const float ring = std::max(1.5f * lw, framing.text_size / 10.0f);
      if (radius >= 4.0f * lw && 10.0f * (ring + 0.8f * radius) <= shorter) {
        if (view.show_forces && mark.force > 0.0 && framing.force_scale > 0.0) {
          list.disc(mark.center, std::max(1.5f * lw, 0.8f * radius * share(mark.force)),
                    palette::force);
          tally.forces = true;
        }
        if (view.show_contacts && mark.active) {
          list.ring(mark.center, radius, ring, palette::contact);
          tally.rings = true;
        }
        continue;
      }
    }
    // Otherwise a mark along the contact face: red where the pairs are active, as wide as
    // their force (at most a twentieth of the shorter strut, straddling both ends).
    const float widest = std::min(4.0f * lw, 0.05f * shorter);
    if (widest < 0.75f || spacing < 2.0f) {
      ++tally.contacts_left_out;
      continue;
    }
    const auto width = [&](double force) {
      return std::clamp((1.0f + 2.0f * share(force)) * lw, 0.75f, widest);
    };
    if (bar) {
      const ContactMark& mark = marks[static_cast<std::size_t>(first)];
      if (!mark.active) continue;
      if (spacing < framing.bar_width + 2.0f * lw) {  // it would reach the next strut
        ++tally.contacts_left_out;
        continue;
      }
      const Point across = perpendicular(mark.normal);
      const float half = 0.5f * (framing.bar_width + lw);
      list.line(mark.center - half * across, mark.center + half * across, width(mark.force),
                palette::contact);
    } else {
      for (int p = first; p + 1 < last; ++p) {
        const ContactMark& m0 = marks[static_cast<std::size_t>(p)];
        const ContactMark& m1 = marks[static_cast<std::size_t>(p + 1)];
        if (!m0.active || !m1.active) continue;
        list.line(m0.center, m1.center, width(0.5 * (m0.force + m1.force)), palette::contact);
      }
    }
    tally.faces = true;
  }
}

// --- labels, legends, caption, scale ----------------------------------------------------

// Strut names beside the struts, where there is room for them without covering a strut.
// The boxes of the triangles drawn into `list` from vertex `first` on (the load arrows):
// what a strut label must not cover. Empty when there are too many to check cheaply.
std::vector<Rect> drawn_boxes(const DrawList& list, std::size_t first, std::size_t labels) {
  const auto& v = list.vertices();
  std::vector<Rect> boxes;
  if ((v.size() - first) / 3 * labels > 4'000'000) return boxes;
  for (std::size_t i = first; i + 2 < v.size(); i += 3) {
    const Point a = v[i].position, b = v[i + 1].position, c = v[i + 2].position;
    boxes.push_back({std::min({a.x, b.x, c.x}), std::min({a.y, b.y, c.y}),
                     std::max({a.x, b.x, c.x}), std::max({a.y, b.y, c.y})});
  }
  return boxes;
}

bool overlaps(const Rect& a, const Rect& b) {
  return a.x0 < b.x1 && b.x0 < a.x1 && a.y0 < b.y1 && b.y0 < a.y1;
}

void draw_labels(DrawList& list, const solver::Model& model, const SceneFraming& framing,
                 const NodeLookup& nodes, GlyphTally& tally, const std::vector<Rect>& taken) {
  const float size = std::round(0.75f * framing.text_size);
  for (std::size_t s = 0; s < model.struts.size(); ++s) {
    const solver::StrutMesh& mesh = model.struts[s];
    const std::string& name = model.strut_names[s];
    const float width = estimated_text_width(name, size);
    const float room = free_px(framing, model, static_cast<int>(s));
    if (room < size + 4.0f || length_px(framing, mesh) < width + 2.0f * size) {
      ++tally.labels_left_out;
      continue;
    }
    // At a third of the strut (the middle is where loads and contacts are least), on its
    // upper side - or, where a load arrow lies there, the first other place along either
    // side that is clear of them.
    const Point upper = upper_side(framing, mesh);
    const auto anchor_at = [&](int i, Point side) {
      const int node = mesh.node(i, mesh.dofs_per_node == 1 ? 0 : mesh.ny / 2);
      const Point at = framing.node(model, static_cast<int>(s), node,
                                    nodes.displacement(static_cast<int>(s), node));
      return at + (half_width_px(framing, mesh) + 0.6f * size + framing.line_width) * side;
    };
    const auto clear = [&](Point anchor) {
      const Rect box{anchor.x - 0.5f * width, anchor.y - 0.6f * size, anchor.x + 0.5f * width,
                     anchor.y + 0.6f * size};
      return std::none_of(taken.begin(), taken.end(),
                          [&](const Rect& t) { return overlaps(box, t); });
    };
    Point anchor = anchor_at(mesh.nx / 3, upper);
    if (!clear(anchor)) {
      for (const Point side : {upper, -1.0f * upper}) {
        bool found = false;
        for (const int i :
             {mesh.nx / 3, mesh.nx / 2, 2 * mesh.nx / 3, mesh.nx / 6, 5 * mesh.nx / 6})
          if (clear(anchor_at(i, side))) {
            anchor = anchor_at(i, side);
            found = true;
            break;
          }
        if (found) break;
      }
    }
    list.text(name, anchor, size, palette::muted, HAlign::Center, VAlign::Middle);
  }
}

// What a value colouring shows: its quantity, the colour map's end, its name, and the
// largest value of the state shown (the scale's "now" when the scale is fixed).
struct ValueLegend {
  scenes::Quantity quantity;
  double scale;
  const char* name;
  double now = 0.0;
  bool keep_name = false;  // drawn even past x1
};

std::string quantity(double value, scenes::Quantity kind, const scenes::Units& units);

// What a scale is: "largest 16.8 kN" (the state shown's), or for a fixed one "scale 78.7 kN:
// largest over loads 0-2; now 16.8 kN" (issue 23, item 4).
std::string scale_note(double scale, double now, const std::string& basis, scenes::Quantity kind,
                       const scenes::Units& units) {
  if (basis.empty()) return "largest " + quantity(scale, kind, units);
  return "scale " + quantity(scale, kind, units) + ": largest " + basis + "; now " +
         quantity(now, kind, units);
}

// Largest |value| of the state shown, per quantity a legend names.
double largest_force_now(const solver::Snapshot& snapshot) {
  double largest = 0.0;
  for (const double f : snapshot.force)
    if (std::isfinite(f)) largest = std::max(largest, std::abs(f));
  return largest;
}

double largest_value_now(const solver::Model& model, const solver::Snapshot& snapshot,
                         ColorBy color) {
  double largest = 0.0;
  if (color == ColorBy::Stress)
    for (const auto& piece : piece_stresses(model, snapshot))
      for (const double s : piece)
        if (std::isfinite(s)) largest = std::max(largest, std::abs(s));
  if (color == ColorBy::Moment && model.frame())
    for (const solver::BeamMoments& piece : solver::piece_moments(model, snapshot))
      for (const auto& ends : piece.ends)
        for (const double m : ends)
          if (std::isfinite(m)) largest = std::max(largest, std::abs(m));
  return largest;
}

// One line: "-420 [colour bar] 420 MPa  axial stress", centred on y; without the name
// when it would run past x1 (into the length scale of a small frame; the information
// panel names the colouring too).
void draw_value_legend(DrawList& list, const SceneFraming& framing, const scenes::Units& units,
                       const ValueLegend& legend, const std::string& basis, float x0, float x1,
                       float y) {
  const float text = framing.text_size, label = 0.8f * text;
  const double scale = legend.scale;
  const scenes::DisplayUnit unit = scenes::display_unit(legend.quantity, units, scale);
  const std::string low = format("%.3g", -scale / unit.divisor);
  list.text(low, {x0, y}, label, palette::ink, HAlign::Left, VAlign::Middle);
  const float bar0 = x0 + estimated_text_width(low, label) + 0.3f * text;
  const float width = std::min(8.0f * text, 0.25f * framing.region.width());
  const float y0 = y - 0.3f * text, y1 = y + 0.3f * text;
  constexpr int kSteps = 48;
  for (int j = 0; j < kSteps; ++j) {
    const float xa = bar0 + width * j / kSteps, xb = bar0 + width * (j + 1) / kSteps;
    const Color ca = diverging(-1.0 + 2.0 * j / kSteps);
    const Color cb = diverging(-1.0 + 2.0 * (j + 1) / kSteps);
    list.triangle({{xa, y0}, ca}, {{xb, y0}, cb}, {{xb, y1}, cb});
    list.triangle({{xa, y0}, ca}, {{xb, y1}, cb}, {{xa, y1}, ca});
  }
  list.rect_outline({bar0, y0, bar0 + width, y1}, framing.line_width, kOutline);
  list.line({bar0 + 0.5f * width, y1}, {bar0 + 0.5f * width, y1 + 0.25f * text}, framing.line_width,
            kOutline);
  const std::string end = format("%.3g", scale / unit.divisor) + " " + unit.name;
  const std::string named = end + "   " + legend.name;
  // The ends are the largest |value| of the state shown, or a fixed scale named as such.
  const std::string what =
      basis.empty() ? "largest shown"
                    : "largest " + basis + "; now " + quantity(legend.now, legend.quantity, units);
  const float at = bar0 + width + 0.3f * text;
  // What fits before x1: the name and what the scale is, the name alone, the end alone;
  // the stress legend always keeps its name (as pictures and tests of it have it).
  const auto fits = [&](const std::string& candidate) {
    return at + estimated_text_width(candidate, label) <= x1;
  };
  const std::string full = named + " (" + what + ")";
  const std::string shown = fits(full) ? full : fits(named) || legend.keep_name ? named : end;
  list.text(shown, {at, y}, label, palette::ink, HAlign::Left, VAlign::Middle);
}

// The moment colouring of a scene without beams: a grey swatch and why it is grey.
void draw_no_moment_legend(DrawList& list, const SceneFraming& framing, float x0, float y) {
  const float text = framing.text_size;
  const Rect swatch{x0, y - 0.3f * text, x0 + 1.6f * text, y + 0.3f * text};
  list.rect(swatch, palette::no_value);
  list.rect_outline(swatch, framing.line_width, kOutline);
  list.text("no bending moment: bars and plane struts carry none", {swatch.x1 + 0.4f * text, y},
            0.8f * text, palette::ink, HAlign::Left, VAlign::Middle);
}

// The length of the scale bar: a round length (1, 2 or 5 x 10^k in the scene's units),
// about a sixth of the region wide; 0 when there is none.
double scale_bar_length(const SceneFraming& framing) {
  const double target = 0.16 * framing.region.width() / framing.pixels_per_unit;
  if (!(target > 0.0) || !std::isfinite(target)) return 0.0;
  const double decade = std::pow(10.0, std::floor(std::log10(target)));
  double world = decade;
  for (double mantissa : {5.0, 2.0, 1.0})
    if (mantissa * decade <= target) {
      world = mantissa * decade;
      break;
    }
  return world;
}

// The scale bar, ending at x1.
void draw_scale_bar(DrawList& list, const SceneFraming& framing, const scenes::Units& units,
                    float x1, float y1) {
  const double world = scale_bar_length(framing);
  if (!(world > 0.0)) return;
  const float pixels = static_cast<float>(world * framing.pixels_per_unit);
  const float lw = framing.line_width, tick = 0.35f * framing.text_size;
  const float x0 = x1 - pixels, y = y1 - 0.2f * framing.text_size;
  list.line({x0, y}, {x1, y}, 2.0f * lw, palette::ink);
  list.line({x0, y + lw}, {x0, y - tick}, lw, palette::ink);
  list.line({x1, y + lw}, {x1, y - tick}, lw, palette::ink);
  list.text(format("%g", world) + " " + units.length, {0.5f * (x0 + x1), y - 0.4f * tick},
            0.8f * framing.text_size, palette::ink, HAlign::Center, VAlign::Bottom);
}

std::string quantity(double value, scenes::Quantity kind, const scenes::Units& units) {
  const scenes::DisplayUnit unit = scenes::display_unit(kind, units, value);
  return format("%.3g", value / unit.divisor) + " " + unit.name;
}

using LegendSample = std::function<void(Point, float)>;  // at the middle left, text size t
using LegendItem = std::pair<std::string, LegendSample>;

// The glyphs present in the picture, each with the function that draws its sample.
std::vector<LegendItem> glyph_items(DrawList& list, const SceneFraming& framing,
                                    const GlyphTally& tally, const scenes::Units& units,
                                    const View& view) {
  const float lw = framing.line_width;
  std::vector<LegendItem> items;
  if (tally.walls)
    items.emplace_back("clamped end", [&list, lw](Point p, float t) {
      const float sample = 1.6f * t;
      const Point top = p + Point{0.5f * sample, -0.45f * t},
                  bottom = p + Point{0.5f * sample, 0.45f * t};
      list.line(top, bottom, 2.0f * lw, palette::wall);
      for (float s = 0.15f * t; s < 0.9f * t; s += 0.3f * t)
        list.line(top + Point{0, s}, top + Point{0.3f * t, s - 0.3f * t}, 1.2f * lw, palette::wall);
    });
  if (tally.pins)
    items.emplace_back("pinned support", [&list, lw](Point p, float t) {
      const Point tip = p + Point{0.8f * t, -0.45f * t};
      const Point left = p + Point{0.35f * t, 0.35f * t}, right = p + Point{1.25f * t, 0.35f * t};
      list.polyline({tip, left, right}, 1.6f * lw, palette::wall, true);
      list.line(p + Point{0.15f * t, 0.5f * t}, p + Point{1.45f * t, 0.5f * t}, 2.0f * lw,
                palette::wall);
    });
  if (tally.rigid_joints)
    items.emplace_back("rigid joint", [&list, lw](Point p, float t) {
      list.rect({p.x + 0.5f * t, p.y - 0.3f * t, p.x + 1.1f * t, p.y + 0.3f * t}, palette::wall);
    });
  if (tally.pinned_joints)
    items.emplace_back("pinned joint", [&list, lw](Point p, float t) {
      list.ring(p + Point{0.8f * t, 0}, 0.3f * t, std::max(1.5f * lw, t / 12.0f), palette::wall);
    });
  if (tally.loads)
    items.emplace_back(
        "load (longest " + quantity(tally.largest_load, scenes::Quantity::Force, units) + ")",
        [&list, lw](Point p, float t) {
          list.arrow(p, p + Point{1.6f * t, 0}, std::max(1.4f * lw, t / 9.0f), 0.6f * t,
                     palette::load);
        });
  if (tally.distributed)
    items.emplace_back(
        "distributed load (" +
            quantity(tally.largest_distributed, scenes::Quantity::ForcePerLength, units) + ")",
        [&list, lw](Point p, float t) {
          const float sample = 1.6f * t;
          list.line(p + Point{0, -0.45f * t}, p + Point{sample, -0.45f * t}, 1.2f * lw,
                    palette::load);
          for (float s : {0.2f, 0.8f})
            list.arrow(p + Point{s * sample, -0.45f * t}, p + Point{s * sample, 0.45f * t},
                       1.2f * lw, 0.4f * t, palette::load);
        });
  if (tally.rings)
    items.emplace_back("active contact", [&list, lw](Point p, float t) {
      list.ring(p + Point{0.8f * t, 0}, 0.4f * t, std::max(1.5f * lw, t / 10.0f), palette::contact);
    });
  if (tally.faces)
    items.emplace_back("active contact (width: force)", [&list, lw](Point p, float t) {
      list.line(p + Point{0.8f * t, -0.5f * t}, p + Point{0.8f * t, 0.5f * t}, 3.0f * lw,
                palette::contact);
    });
  if (tally.forces && view.show_forces)
    items.emplace_back("contact force (" +
                           scale_note(framing.force_scale, tally.largest_force_now,
                                      view.scale_basis, scenes::Quantity::Force, units) +
                           ")",
                       [&list, lw](Point p, float t) {
                         list.disc(p + Point{0.8f * t, 0}, 0.35f * t, palette::force);
                       });
  if (tally.gaps)
    items.emplace_back("open gap", [&list, lw](Point p, float t) {
      list.dashed_line(p, p + Point{1.6f * t, 0}, 1.2f * lw, 3.0f * lw, 2.5f * lw, palette::gap);
    });
  return items;
}

// What was too dense to draw ("3 loads, 12 contact marks"); "" when nothing was left out.
std::string left_out_note(const GlyphTally& tally, const View& view) {
  std::string left_out;
  if (tally.loads_left_out > 0) left_out += std::to_string(tally.loads_left_out) + " loads";
  if (tally.contacts_left_out > 0)
    left_out +=
        (left_out.empty() ? "" : ", ") + std::to_string(tally.contacts_left_out) + " contact marks";
  if (view.show_labels && tally.labels_left_out > 0)
    left_out += (left_out.empty() ? "" : ", ") + std::to_string(tally.labels_left_out) + " labels";
  return left_out;
}

// The legend's items in rows within `band`, at the largest text size (down to 60%, not below
// the smallest legible one) that needs no more rows than the band holds.
void lay_out_legend(DrawList& list, const SceneFraming& framing,
                    const std::vector<LegendItem>& items, Rect band) {
  // Rows the band holds at full size; the largest size (down to 60%) that needs no more.
  const float full = framing.text_size;
  const int rows = std::max(1, 1 + static_cast<int>((band.y1 - band.y0) / (1.3f * full)));
  const auto item_width = [&](const auto& item, float t) {
    return (item.second ? 2.0f * t : 0.0f) + estimated_text_width(item.first, 0.8f * t) + 1.0f * t;
  };
  const auto rows_needed = [&](float t) {
    int count = 1;
    float x = band.x0;
    for (const auto& item : items) {
      const float width = item_width(item, t);
      if (x > band.x0 && x + width > band.x1) {
        ++count;
        x = band.x0;
      }
      x += width;
    }
    return count;
  };
  // Not below the smallest legible text (its text is 0.8 t): more rows instead, upward.
  const float least = framing.smallest_text / 0.8f;
  float t = full;
  while (t > 0.6f * full && 0.9f * t >= least && rows_needed(t) > rows)
    t *= 0.9f;
  t = std::max(t, least);
  const int needed = rows_needed(t);
  const bool grow = least > 0.0f && needed > rows;
  const float row_height =
      grow ? 1.3f * t : std::min(1.3f * t, (band.y1 - band.y0) / std::max(1, needed - 1));
  float x = band.x0, y = grow ? band.y1 - row_height * static_cast<float>(needed - 1) : band.y0;
  for (const auto& item : items) {
    const float width = item_width(item, t);
    if (x > band.x0 && x + width > band.x1) {
      x = band.x0;
      y += row_height;
    }
    if (item.second) item.second(Point{x, y}, t);
    list.text(item.first, {x + (item.second ? 2.0f * t : 0.0f), y}, 0.8f * t, palette::ink,
              HAlign::Left, VAlign::Middle);
    x += width;
  }
}

// The glyphs present, each with a small sample, in rows that wrap within `band` (its top
// is the middle of the first row); set smaller when they would need more rows than it has.
void draw_glyph_legend(DrawList& list, const SceneFraming& framing, const GlyphTally& tally,
                       const scenes::Units& units, const View& view, Rect band) {
  std::vector<LegendItem> items = glyph_items(list, framing, tally, units, view);
  if (const std::string left_out = left_out_note(tally, view); !left_out.empty())
    items.emplace_back("too dense to draw at this size: " + left_out, LegendSample());
  if (items.empty()) return;
  lay_out_legend(list, framing, items, band);
}

void draw_caption(DrawList& list, const solver::Snapshot& snapshot, const SceneFraming& framing,
                  const SceneCaption& caption, const scenes::Units& units) {
  std::string text, limit;
  if (!caption.method.empty()) text += caption.method + "  ·  ";
  text += "load factor " + format("%.4g", snapshot.load_factor);
  if (!caption.load_step.empty()) text += " (" + caption.load_step + ")";
  text += "  ·  iteration " + std::to_string(snapshot.iteration);
  text += std::string("  ·  ") +
          (framing.gaps_magnified ? "displacements and gaps " : "displacements ") +
          times(framing.magnification);
  if (framing.limited_by == "crossing") limit = " (more would make struts cross)";
  if (framing.limited_by == "gaps") limit = " (more would not leave the struts room for the gaps)";
  if (framing.limited_by == "elements") limit = " (more would turn elements inside out)";
  const std::string unit_names =
      "  ·  " + units.length + ", " + units.force + ", " + scenes::stress_unit(units);
  const float room = framing.region.width() - 2.0f * framing.text_size;
  const auto fitted = [&](const std::string& line) {
    const float size = 0.85f * framing.text_size;
    const float width = estimated_text_width(line, size);
    return width > room ? std::max(0.6f * framing.text_size, size * room / width) : size;
  };
  // Where the line would need text below the smallest legible size, the reason for the
  // magnification goes first, then the units (the legends name them too).
  float size = fitted(text + limit + unit_names);
  if (size >= framing.smallest_text)
    text += limit + unit_names;
  else if ((size = fitted(text + unit_names)) >= framing.smallest_text)
    text += unit_names;
  else
    size = fitted(text);
  size = std::max(size, framing.smallest_text);
  list.text(text,
            {framing.region.x0 + framing.text_size, framing.region.y0 + 0.4f * framing.text_size},
            size, palette::muted, HAlign::Left, VAlign::Top);
}

}  // namespace

std::vector<ContactMark> contact_marks(const solver::Model& model, const solver::Snapshot& snapshot,
                                       const SceneFraming& framing) {
  const NodeLookup nodes(model, snapshot);
  std::vector<ContactMark> marks;
  marks.reserve(model.pairs.size());
  for (std::size_t p = 0; p < model.pairs.size(); ++p) {
    const solver::ContactPair& pair = model.pairs[p];
    ContactMark mark;
    mark.pair = static_cast<int>(p);
    mark.a = framing.node(model, pair.strut_a, pair.node_a,
                          nodes.displacement(pair.strut_a, pair.node_a));
    mark.b = framing.node(model, pair.strut_b, pair.node_b,
                          nodes.displacement(pair.strut_b, pair.node_b));
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

DrawList draw_glyphs(const solver::Model& model, const solver::Snapshot& snapshot, const View& view,
                     const SceneFraming& framing, const SceneCaption& caption) {
  DrawList list;
  GlyphTally tally;
  const NodeLookup nodes(model, snapshot);
  if (view.show_supports) draw_supports(list, model, framing, nodes, tally);
  draw_gaps_and_contacts(list, model, snapshot, view, framing, tally);
  const std::size_t loads_from = list.vertices().size();
  if (view.show_loads)
    for (const scenes::Load& load : model.scene_loads) {
      if (load.per_length)
        draw_distributed_load(list, model, framing, nodes, load, snapshot.load_factor, tally);
      else
        draw_point_load(list, model, framing, nodes, load, snapshot.load_factor, tally);
    }
  if (view.show_labels)
    draw_labels(list, model, framing, nodes, tally,
                drawn_boxes(list, loads_from, model.struts.size()));

  // What the frame shows: the caption above; below, two rows of glyph legend, then the
  // stress or moment colours (left) and the length scale (right).
  const float t = framing.text_size;
  draw_caption(list, snapshot, framing, caption, model.units);
  const Rect& region = framing.region;
  const float bottom_row = region.y1 - 0.9f * t;
  if (view.show_scale)
    draw_scale_bar(list, framing, model.units, region.x1 - t, bottom_row + 0.4f * t);
  // The value legends end half a text size before the scale bar's label: what their scale
  // is, then their long name, dropped in a small frame.
  const float legend_end =
      view.show_scale
          ? region.x1 - t -
                static_cast<float>(scale_bar_length(framing) * framing.pixels_per_unit) - 0.5f * t
          : region.x1 - t;
  if (view.color_by == ColorBy::Stress)
    draw_value_legend(list, framing, model.units,
                      {scenes::Quantity::Stress, framing.stress_scale, "axial stress",
                       largest_value_now(model, snapshot, ColorBy::Stress), true},
                      view.scale_basis, region.x0 + t, legend_end, bottom_row);
  if (view.color_by == ColorBy::Moment && model.frame())
    draw_value_legend(list, framing, model.units,
                      {scenes::Quantity::Moment, framing.moment_scale, "bending moment",
                       largest_value_now(model, snapshot, ColorBy::Moment)},
                      view.scale_basis, region.x0 + t, legend_end, bottom_row);
  else if (view.color_by == ColorBy::Moment)
    draw_no_moment_legend(list, framing, region.x0 + t, bottom_row);
  tally.largest_force_now = largest_force_now(snapshot);
  if (view.show_legend)
    draw_glyph_legend(list, framing, tally, model.units, view,
                      {region.x0 + t, region.y1 - 3.5f * t, region.x1 - t, region.y1 - 2.2f * t});
  return list;
}

DrawList draw_scene(const solver::Model& model, const solver::Snapshot& snapshot, const View& view,
                    const SceneFraming& framing, const SceneCaption& caption) {
  DrawList list;
  const SceneMesh mesh = build_scene_mesh(model, snapshot, framing, view.color_by);
  MeshValues values;
  fill_mesh_values(mesh, model, snapshot, framing, values);
  expand_mesh(mesh, values, mesh_uniforms(mesh, framing), list);
  list.append(draw_glyphs(model, snapshot, view, framing, caption));
  return list;
}

}  // namespace fetic::render
