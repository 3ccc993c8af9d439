#pragma once
// Geometry the contract defines on struts and contacts (SCENES.md): axes, ends,
// contact normals and gaps. Shared by validation and by the solver's model.

#include "scenes/scene.hpp"

namespace fetic::scenes {

double distance(Point p, Point q);
double length(const Strut& strut);
Point axis(const Strut& strut);  // unit vector from 'from' to 'to'
Point end_point(const Strut& strut, StrutEnd end);
// Unit vector along the axis pointing out of the strut at that end.
Point outward(const Strut& strut, StrutEnd end);

// Relative size below which a negative gap is rounding of coordinates, taken as zero.
inline constexpr double kGapRoundingTolerance = 1e-9;

struct ContactGeometry {
  Point normal{};             // unit, along a's axis, from a's end toward b's end
  double gap = 0.0;           // along the normal, a's end to b's end (reference state); rounding
                              // below kGapRoundingTolerance x strut length is taken as zero
  double offset = 0.0;        // distance of b's end from a's axis line (0 when collinear)
  double misalignment = 0.0;  // |sin| of the angle between the two axes
  bool b_faces_a = false;     // b's end points back toward a along -normal
};
ContactGeometry contact_geometry(const Scene& scene, const Contact& contact);

// Reference position of the node a reference names (bar and frame model: along the axis,
// node k at k / elements of the way from 'from' to 'to', the ends exact).
Point node_point(const Scene& scene, EndRef ref);

// Frame model (SCENES.md "Frame model"): the contact normal is the given unit vector, or
// (x_b - x_a) / |x_b - x_a|; the gap g = n.(x_b - x_a), a negative g within
// kGapRoundingTolerance x the longer strut taken as zero.
struct FrameContactGeometry {
  Point normal{};  // unit; (0, 0) when the nodes coincide and no normal is given
  double gap = 0.0;
  double distance = 0.0;  // |x_b - x_a|
  bool coincide = false;  // the nodes are at one point (within the rounding tolerance)
};
FrameContactGeometry frame_contact_geometry(const Scene& scene, const Contact& contact);

}  // namespace fetic::scenes
