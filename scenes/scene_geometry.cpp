#include "scenes/scene_geometry.hpp"

#include <algorithm>
#include <cmath>

namespace fetic::scenes {

double distance(Point p, Point q) {
  return std::hypot(q[0] - p[0], q[1] - p[1]);
}

double length(const Strut& strut) {
  return distance(strut.from, strut.to);
}

Point axis(const Strut& strut) {
  const double l = length(strut);
  return {(strut.to[0] - strut.from[0]) / l, (strut.to[1] - strut.from[1]) / l};
}

Point end_point(const Strut& strut, StrutEnd end) {
  return end == StrutEnd::From ? strut.from : strut.to;
}

Point outward(const Strut& strut, StrutEnd end) {
  const Point e = axis(strut);
  return end == StrutEnd::To ? e : Point{-e[0], -e[1]};
}

ContactGeometry contact_geometry(const Scene& scene, const Contact& contact) {
  const Strut& a = scene.struts.at(contact.a.strut);
  const Strut& b = scene.struts.at(contact.b.strut);
  ContactGeometry g;
  // The normal points from a's end toward b's end along a's axis: for facing ends that
  // is a's outward direction, which stays defined when the gap is zero.
  g.normal = outward(a, contact.a.end);
  const Point pa = end_point(a, contact.a.end);
  const Point pb = end_point(b, contact.b.end);
  const double dx = pb[0] - pa[0];
  const double dy = pb[1] - pa[1];
  g.gap = dx * g.normal[0] + dy * g.normal[1];
  const double scale = std::max(length(a), length(b));
  if (g.gap < 0.0 && g.gap >= -kGapRoundingTolerance * scale) g.gap = 0.0;
  g.offset = std::abs(-dx * g.normal[1] + dy * g.normal[0]);
  const Point ob = outward(b, contact.b.end);
  g.misalignment = std::abs(ob[0] * g.normal[1] - ob[1] * g.normal[0]);
  g.b_faces_a = ob[0] * g.normal[0] + ob[1] * g.normal[1] < 0.0;
  return g;
}

Point node_point(const Scene& scene, EndRef ref) {
  const Strut& strut = scene.struts.at(ref.strut);
  const int k = node_index(scene, ref);
  if (k == 0) return strut.from;
  if (k >= strut.elements) return strut.to;
  // The same interpolation as the solver's mesh, so that both agree to the last bit.
  const double s = static_cast<double>(k) / strut.elements;
  return {(1.0 - s) * strut.from[0] + s * strut.to[0], (1.0 - s) * strut.from[1] + s * strut.to[1]};
}

FrameContactGeometry frame_contact_geometry(const Scene& scene, const Contact& contact) {
  FrameContactGeometry g;
  const Point pa = node_point(scene, contact.a);
  const Point pb = node_point(scene, contact.b);
  const double dx = pb[0] - pa[0], dy = pb[1] - pa[1];
  g.distance = std::hypot(dx, dy);
  const double scale =
      std::max(length(scene.struts.at(contact.a.strut)), length(scene.struts.at(contact.b.strut)));
  g.coincide = g.distance <= kGapRoundingTolerance * scale;
  if (contact.has_normal) {
    const double size = std::hypot(contact.normal[0], contact.normal[1]);
    g.normal = {contact.normal[0] / size, contact.normal[1] / size};
  } else if (!g.coincide) {
    g.normal = {dx / g.distance, dy / g.distance};
  }
  g.gap = g.coincide ? 0.0 : dx * g.normal[0] + dy * g.normal[1];
  if (g.gap < 0.0 && g.gap >= -kGapRoundingTolerance * scale) g.gap = 0.0;
  return g;
}

}  // namespace fetic::scenes
