#pragma once
// Frame model: which motions the supports and joints leave free, and which of those no
// contact can stop (a mechanism).
//
// A strut's beam stiffness vanishes exactly on its three rigid-body motions, so the
// motions that cost no energy are those in which every strut moves as a rigid body and
// the supports and joints are respected. Struts joined by rigid joints move as one body;
// a strut with a clamped end does not move. What is left is a small linear system over
// three parameters per body (two translations, one rotation), solved per group of struts
// that joints connect: its null space (SVD, relative threshold 1e-9) is the basis of free
// motions. The validation refuses a scene where some free motion changes no contact gap
// (nothing can ever hold it); the solver uses the same basis as the kernel of the
// assembled stiffness, to place groups the active contacts leave free, and to decide
// whether a load pushes a free group away from every contact (unbounded).

#include <array>
#include <vector>

#include "scenes/scene.hpp"

namespace fetic::scenes {

// One free motion of one joint-connected group of struts: strut s of the group moves
// rigidly, u(p) = (a - theta (p_y - c_y), b + theta (p_x - c_x)), rotation theta.
struct FreeMotion {
  int group = 0;
  Point centre{};                               // c: the group's centre
  std::vector<std::array<double, 3>> of_strut;  // (a, b, theta) per strut of the group
};

struct FrameKinematics {
  std::vector<int> group_of_strut;
  std::vector<int> position_in_group;    // per strut: its index in groups[group_of_strut]
  std::vector<std::vector<int>> groups;  // struts connected by joints, in increasing order
  std::vector<FreeMotion> motions;       // orthonormal per group (translations and rotation
                                         // scaled by the group's size)
};

FrameKinematics frame_kinematics(const Scene& scene);

// Displacement (ux, uy) and rotation of point p of strut `strut` in a motion.
std::array<double, 3> motion_at(const FrameKinematics& kinematics, const FreeMotion& motion,
                                int strut, Point p);

// Groups of struts that some free motion moves without changing any contact gap: each a
// list of struts (in increasing order) and a description of one such motion, e.g.
// "it can rotate about (0, 2)".
struct Mechanism {
  std::vector<int> struts;
  std::string motion;
};
std::vector<Mechanism> frame_mechanisms(const Scene& scene, const FrameKinematics& kinematics);

}  // namespace fetic::scenes
