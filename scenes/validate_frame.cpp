// Cross-checks of a frame scene (SCENES.md "Frame model"): joints, contacts in any
// direction, magnitudes of the bending stiffness and moments, and mechanisms.

#include "scenes/validate_frame.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <sstream>
#include <tuple>

#include "scenes/frame_mechanisms.hpp"
#include "scenes/magnitudes.hpp"
#include "scenes/message_text.hpp"
#include "scenes/scene_geometry.hpp"
#include "scenes/units.hpp"

namespace fetic::scenes {
namespace {

// A (strut, node) key.
using NodeKey = std::pair<int, int>;

NodeKey key(const Scene& scene, EndRef ref) {
  return {ref.strut, node_index(scene, ref)};
}

void check_magnitudes(const Scene& scene, std::vector<Problem>& problems) {
  for (const Strut& strut : scene.struts) {
    const double h = length(strut) / strut.elements;
    const double bending = strut.E * strut.inertia / (h * h * h);
    if (outside_magnitude_range(bending))
      problems.push_back({strut.line, "strut " + quoted(strut.name) +
                                          ": element bending stiffness E * inertia / element "
                                          "length^3 = " +
                                          number_text(bending) + " " +
                                          force_per_length_unit(scene.units) + " is " +
                                          magnitude_range_text()});
  }
  for (const Load& load : scene.loads) {
    if (load.moment == 0.0) continue;
    if (outside_magnitude_range(load.moment))
      problems.push_back({load.line, "load on strut " + quoted(scene.struts[load.strut].name) +
                                         ": moment " + number_text(load.moment) + " " +
                                         scene.units.force + " " + scene.units.length + " is " +
                                         magnitude_range_text() + "; write 0 for no moment"});
  }
}

void check_joints(const Scene& scene, std::vector<Problem>& problems,
                  std::map<NodeKey, int>& joint_of_node) {
  for (size_t j = 0; j < scene.joints.size(); ++j) {
    const Joint& joint = scene.joints[j];
    std::string label = "joint";
    for (const EndRef& end : joint.ends)
      label += (label == "joint" ? " " : ", ") + end_label(scene, end);
    if (joint.ends.size() > kMaxJointEnds) {
      problems.push_back({joint.line, label.substr(0, 60) + "...: a joint connects at most " +
                                          std::to_string(kMaxJointEnds) + " ends, this one " +
                                          std::to_string(joint.ends.size())});
      continue;
    }
    const Point first = end_point(scene.struts[joint.ends[0].strut], joint.ends[0].end);
    double scale = 0.0;
    for (const EndRef& end : joint.ends)
      scale = std::max(scale, length(scene.struts[end.strut]));
    for (const EndRef& end : joint.ends) {
      const auto [it, inserted] = joint_of_node.emplace(key(scene, end), static_cast<int>(j));
      if (!inserted) {
        const Joint& other = scene.joints[it->second];
        problems.push_back(
            {joint.line,
             label + ": the end " + end_label(scene, end) +
                 (it->second == static_cast<int>(j)
                      ? " is listed twice"
                      : " is already in the joint on line " + std::to_string(other.line) +
                            " (list all ends that meet at a point in one joint)")});
        continue;
      }
      const Point p = end_point(scene.struts[end.strut], end.end);
      const double apart = distance(p, first);
      if (apart > kGapRoundingTolerance * scale)
        problems.push_back({joint.line, label + ": the ends do not meet at one point: " +
                                            end_label(scene, end) + " is " + number_text(apart) +
                                            " away from " + end_label(scene, joint.ends[0])});
    }
  }
}

void check_contacts(const Scene& scene, const std::map<NodeKey, int>& joint_of_node,
                    std::vector<Problem>& problems, std::vector<Problem>& warnings) {
  // (strut a, node a, strut b, node b) of earlier contacts with their normals and lines.
  std::map<std::tuple<int, int, int, int>, std::vector<std::pair<Point, int>>> seen;
  for (const Contact& contact : scene.contacts) {
    const std::string label =
        "contact " + end_label(scene, contact.a) + " - " + end_label(scene, contact.b);
    if (contact.a.strut == contact.b.strut) {
      problems.push_back(
          {contact.line, label + ": a contact joins the nodes of two different struts"});
      continue;
    }
    const NodeKey a = key(scene, contact.a), b = key(scene, contact.b);
    const auto ja = joint_of_node.find(a), jb = joint_of_node.find(b);
    if (ja != joint_of_node.end() && jb != joint_of_node.end() && ja->second == jb->second) {
      problems.push_back({contact.line, label + ": both nodes belong to the joint on line " +
                                            std::to_string(scene.joints[ja->second].line) +
                                            ", which already holds them together"});
      continue;
    }
    const FrameContactGeometry g = frame_contact_geometry(scene, contact);
    if (g.coincide && !contact.has_normal) {
      problems.push_back({contact.line, label +
                                            ": the two nodes coincide, so the contact needs a "
                                            "'normal' (a unit vector pointing from a toward b)"});
      continue;
    }
    const double scale =
        std::max(length(scene.struts[contact.a.strut]), length(scene.struts[contact.b.strut]));
    if (g.gap < 0.0) {
      problems.push_back({contact.line, label + ": b lies " + number_text(-g.gap) +
                                            " behind a along the normal (a negative gap is not "
                                            "allowed; the normal points from a toward b)"});
      continue;
    }
    // Same node pair (either order) and the same line of action as an earlier contact.
    const bool swapped = b < a;
    const auto pair_key = swapped ? std::make_tuple(b.first, b.second, a.first, a.second)
                                  : std::make_tuple(a.first, a.second, b.first, b.second);
    const Point n = swapped ? Point{-g.normal[0], -g.normal[1]} : g.normal;
    for (const auto& [other, line] : seen[pair_key])
      if (std::abs(other[0] * n[1] - other[1] * n[0]) < 1e-9)
        problems.push_back({contact.line, label + ": the same two nodes are already in contact " +
                                              "along the same line on line " +
                                              std::to_string(line)});
    seen[pair_key].push_back({n, contact.line});
    const Point pa = node_point(scene, contact.a), pb = node_point(scene, contact.b);
    const double size =
        std::max({std::abs(pa[0]), std::abs(pa[1]), std::abs(pb[0]), std::abs(pb[1]), scale});
    if (g.gap > 0.0 && g.gap < 1e-9 * size)
      warnings.push_back({contact.line, label + ": the gap " + number_text(g.gap) +
                                            " is at the resolution of the coordinates (about " +
                                            number_text(2.2e-16 * size) +
                                            "); it follows from their last digits"});
  }
}

void check_mechanisms(const Scene& scene, std::vector<Problem>& problems,
                      const std::function<bool()>& stop) {
  for (const Mechanism& mechanism : frame_mechanisms(scene, stop)) {
    std::string names;
    for (size_t i = 0; i < mechanism.struts.size() && i < 8; ++i)
      names += (names.empty() ? "" : ", ") + quoted(scene.struts[mechanism.struts[i]].name);
    if (mechanism.struts.size() > 8)
      names += " and " + std::to_string(mechanism.struts.size() - 8) + " more";
    const bool one = mechanism.struts.size() == 1;
    problems.push_back(
        {scene.struts[mechanism.struts.front()].line,
         (one ? "strut " + names + " is a mechanism: supports, joints and contacts cannot hold it ("
              : "struts " + names +
                    " form a mechanism: supports, joints and contacts cannot hold them (") +
             mechanism.motion + " without touching any contact)"});
  }
}

}  // namespace

void validate_frame(Scene& scene, std::vector<Problem>& problems,
                    const std::function<bool()>& stop) {
  check_magnitudes(scene, problems);
  std::map<NodeKey, int> joint_of_node;
  check_joints(scene, problems, joint_of_node);
  check_contacts(scene, joint_of_node, problems, scene.warnings);
  if (problems.empty()) check_mechanisms(scene, problems, stop);
}

}  // namespace fetic::scenes
