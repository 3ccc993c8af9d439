#include "scenes/validate_scene.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <sstream>

#include "scenes/load_scene.hpp"
#include "scenes/magnitudes.hpp"
#include "scenes/message_text.hpp"
#include "scenes/scene_geometry.hpp"
#include "scenes/validate_frame.hpp"

namespace fetic::scenes {
namespace {

// Geometric comparisons are relative to the size of the struts involved.
constexpr double kRelativeTolerance = kGapRoundingTolerance;

void check_strut_geometry(const Scene& scene, std::vector<Problem>& problems) {
  for (const Strut& strut : scene.struts) {
    const double l = length(strut);
    const double size = std::max({std::abs(strut.from[0]), std::abs(strut.from[1]),
                                  std::abs(strut.to[0]), std::abs(strut.to[1])});
    if (!std::isfinite(l)) {
      problems.push_back({strut.line, "strut " + quoted(strut.name) +
                                          ": coordinates too large to compute its length"});
    } else if (l == 0.0) {
      problems.push_back(
          {strut.line, "strut " + quoted(strut.name) + ": 'from' and 'to' coincide (zero length)"});
    } else if (!(l > kRelativeTolerance * size)) {
      // Coordinates near 1e17 are only as exact as 16 m: a strut that short there is
      // rounding, not geometry.
      problems.push_back(
          {strut.line, "strut " + quoted(strut.name) + ": its length " + number_text(l) +
                           " is below the resolution of its coordinates (they reach " +
                           number_text(size) + "; a length must exceed " +
                           number_text(kRelativeTolerance) +
                           " of them); move the scene nearer the origin"});
    }
  }
  const long long total = unknowns(scene);
  if (total > kMaxUnknowns)
    problems.push_back({0, "the scene has " + std::to_string(total) +
                               " unknowns, more than the limit of " +
                               std::to_string(kMaxUnknowns)});
}

// Stiffness of one element: E A / h for a bar (and a beam's axial stiffness), E t for a
// plane element (independent of its size); the displacement scale is force over this.
double element_stiffness(const Scene& scene, const Strut& strut) {
  if (scene.model != ModelKind::Plane) return strut.E * strut.area * strut.elements / length(strut);
  return strut.E * strut.thickness;
}

void check_magnitudes(const Scene& scene, std::vector<Problem>& problems) {
  for (const Strut& strut : scene.struts) {
    const double l = length(strut);
    if (outside_magnitude_range(l))
      problems.push_back({strut.line, "strut " + quoted(strut.name) + ": length " + number_text(l) +
                                          " " + scene.units.length + " is " +
                                          magnitude_range_text()});
    const double k = element_stiffness(scene, strut);
    if (outside_magnitude_range(k))
      problems.push_back(
          {strut.line, "strut " + quoted(strut.name) + ": element stiffness " +
                           (scene.model != ModelKind::Plane ? "E * area / element length = "
                                                            : "E * thickness = ") +
                           number_text(k) + " " + force_per_length_unit(scene.units) + " is " +
                           magnitude_range_text()});
  }
  for (const Load& load : scene.loads) {
    const double size = std::hypot(load.force[0], load.force[1]);
    if (size == 0.0) continue;  // an explicit zero load is fine
    const double total = load.per_length ? size * length(scene.struts[load.strut]) : size;
    if (outside_magnitude_range(total))
      problems.push_back({load.line, "load on strut " + quoted(scene.struts[load.strut].name) +
                                         ": force " + number_text(total) + " " + scene.units.force +
                                         " is " + magnitude_range_text() +
                                         "; write 0 for no load"});
  }
}

// Bilinear elements much longer than wide (or the reverse) lock in bending and make the
// stiffness ill-conditioned: still valid, but the user should know before a solve stalls.
constexpr double kAspectRatioWarning = 1e3;

void check_element_shapes(const Scene& scene, std::vector<Problem>& warnings) {
  if (scene.model != ModelKind::Plane) return;
  for (const Strut& strut : scene.struts) {
    const double along = length(strut) / strut.elements;
    const double across = strut.height / strut.elements_across;
    const double ratio = std::max(along / across, across / along);
    if (ratio > kAspectRatioWarning)
      warnings.push_back({strut.line, "strut " + quoted(strut.name) + ": its elements are " +
                                          number_text(along) + " by " + number_text(across) + " " +
                                          scene.units.length + " (aspect ratio " +
                                          number_text(ratio) +
                                          "); expect an ill-conditioned stiffness and slow or "
                                          "stalled iterations"});
  }
}

void check_contacts(const Scene& scene, std::vector<Problem>& problems,
                    std::vector<Problem>& warnings) {
  std::map<std::pair<int, int>, int> end_used;  // (strut, end) -> line of first contact
  for (const Contact& contact : scene.contacts) {
    const std::string label =
        "contact " + end_label(scene, contact.a) + " - " + end_label(scene, contact.b);
    for (EndRef ref : {contact.a, contact.b}) {
      auto [it, inserted] =
          end_used.emplace(std::make_pair(ref.strut, static_cast<int>(ref.end)), contact.line);
      if (!inserted && it->second != contact.line)
        problems.push_back({contact.line, label + ": strut end " + end_label(scene, ref) +
                                              " is already in the contact on line " +
                                              std::to_string(it->second) +
                                              " (an end takes part in at most one contact)"});
    }
    if (contact.a.strut == contact.b.strut) {
      problems.push_back(
          {contact.line, label + ": a contact joins the ends of two different struts"});
      continue;
    }
    const Strut& a = scene.struts[contact.a.strut];
    const Strut& b = scene.struts[contact.b.strut];
    if (!(length(a) > 0.0) || !(length(b) > 0.0) || !std::isfinite(length(a)) ||
        !std::isfinite(length(b)))
      continue;  // already reported as a degenerate strut
    const ContactGeometry g = contact_geometry(scene, contact);
    const double scale = std::max(length(a), length(b));
    if (g.misalignment > 1e-6 || !g.b_faces_a) {
      problems.push_back({contact.line, label + ": the ends do not face each other along a "
                                                "common axis (the struts must be collinear, "
                                                "end facing end)"});
      continue;
    }
    if (g.offset > 1e-6 * scale) {
      problems.push_back({contact.line, label +
                                            ": the struts are parallel but not collinear "
                                            "(offset " +
                                            number_text(g.offset) + " across the axis)"});
      continue;
    }
    if (g.gap < -kRelativeTolerance * scale) {
      problems.push_back({contact.line, label + ": the ends overlap by " + number_text(-g.gap) +
                                            " (a negative gap is not allowed)"});
      continue;
    }
    // A gap far below the size of the coordinates is only as exact as their last digits.
    const Point pa = end_point(a, contact.a.end), pb = end_point(b, contact.b.end);
    const double size =
        std::max({std::abs(pa[0]), std::abs(pa[1]), std::abs(pb[0]), std::abs(pb[1]), scale});
    if (g.gap > 0.0 && g.gap < 1e-9 * size)
      warnings.push_back({contact.line, label + ": the gap " + number_text(g.gap) + " " +
                                            scene.units.length +
                                            " is at the resolution of the coordinates (about " +
                                            number_text(2.2e-16 * size) + " " + scene.units.length +
                                            "); it follows from their last digits"});
    if (scene.model == ModelKind::Plane && a.elements_across != b.elements_across)
      problems.push_back({contact.line, label +
                                            ": the end faces have different numbers of "
                                            "nodes (" +
                                            std::to_string(a.elements_across + 1) + " and " +
                                            std::to_string(b.elements_across + 1) +
                                            "); node-to-node contact pairs them one by one"});
    else if (scene.model == ModelKind::Plane &&
             std::abs(a.height - b.height) > kRelativeTolerance * std::max(a.height, b.height))
      warnings.push_back({contact.line, label + ": the end faces have different heights (" +
                                            number_text(a.height) + " and " +
                                            number_text(b.height) +
                                            "); node-to-node contact pairs their nodes by "
                                            "order across the face, not by position, so "
                                            "paired nodes sit up to " +
                                            number_text(std::abs(a.height - b.height) / 2) +
                                            " apart across the axis"});
  }
}

// Bar model: a strut carries only axial displacement, so only the axial component of a
// force counts (SCENES.md). A sideways component is dropped: valid, but say so.
void check_bar_loads(const Scene& scene, std::vector<Problem>& warnings) {
  for (const Load& load : scene.loads) {
    const Point t = axis(scene.struts[load.strut]);
    const double along = load.force[0] * t[0] + load.force[1] * t[1];
    const double across = load.force[1] * t[0] - load.force[0] * t[1];
    const double size = std::hypot(load.force[0], load.force[1]);
    if (!(std::abs(across) > kRelativeTolerance * size)) continue;
    const std::string unit =
        " " + (load.per_length ? force_per_length_unit(scene.units) : scene.units.force);
    warnings.push_back({load.line, "load on strut " + quoted(scene.struts[load.strut].name) +
                                       ": the bar model carries only the axial component of a "
                                       "force; the sideways component " +
                                       number_text(across) + unit +
                                       " is dropped (axial: " + number_text(along) + unit + ")"});
  }
}

// Bar model: every group of struts linked by contacts needs a clamped strut.
void check_bar_struts_held(const Scene& scene, std::vector<Problem>& problems) {
  std::vector<int> parent(scene.struts.size());
  std::iota(parent.begin(), parent.end(), 0);
  auto root = [&](int i) {
    while (parent[i] != i)
      i = parent[i] = parent[parent[i]];
    return i;
  };
  for (const Contact& contact : scene.contacts)
    parent[root(contact.a.strut)] = root(contact.b.strut);
  std::map<int, bool> group_held;
  for (size_t i = 0; i < scene.struts.size(); ++i)
    group_held[root(static_cast<int>(i))] |= scene.struts[i].clamped();
  for (size_t i = 0; i < scene.struts.size(); ++i) {
    if (group_held[root(static_cast<int>(i))]) continue;
    const Strut& strut = scene.struts[i];
    problems.push_back(
        {strut.line, "strut " + quoted(strut.name) +
                         " can be held by no support: it has no clamped end (fixed = "
                         "[\"from\"], [\"to\"] or both) and no chain of contacts leads to a "
                         "strut that has one"});
  }
}

// Plane model: a frictionless end-face contact cannot stop a strut from sliding across
// its axis, so every strut needs a clamped end of its own.
void check_plane_struts_held(const Scene& scene, std::vector<Problem>& problems) {
  for (const Strut& strut : scene.struts)
    if (!strut.clamped())
      problems.push_back({strut.line, "strut " + quoted(strut.name) +
                                          " has no clamped end: in the plane model its "
                                          "frictionless contacts cannot hold it across its axis"});
}

}  // namespace

std::vector<Problem> validate_scene(Scene& scene, const std::function<bool()>& stop) {
  std::vector<Problem> problems;
  scene.warnings.clear();
  check_strut_geometry(scene, problems);
  if (!problems.empty()) return problems;
  check_magnitudes(scene, problems);
  if (!problems.empty()) return problems;
  if (scene.model == ModelKind::Frame) {
    validate_frame(scene, problems, stop);
    return problems;
  }
  check_contacts(scene, problems, scene.warnings);
  check_element_shapes(scene, scene.warnings);
  if (scene.model == ModelKind::Bar) check_bar_loads(scene, scene.warnings);
  if (scene.model == ModelKind::Bar)
    check_bar_struts_held(scene, problems);
  else
    check_plane_struts_held(scene, problems);
  return problems;
}

}  // namespace fetic::scenes
