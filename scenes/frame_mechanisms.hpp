#pragma once
// The frame model's mechanism check, near-linear in the scene's size: sets of struts that
// some free motion moves without changing any contact gap (frame_kinematics.hpp).
//
// Computed from the sparse constraints of supports, joints and contacts, per set of
// struts that joints and contacts link: a dense SVD for small sets, SuiteSparseQR
// (sparse_null_space.hpp) for large ones - a rope of 2,000 pinned struts took 142 s and
// 1.6 GB by one dense SVD, and takes a fraction of a second. Each mechanism lists the
// struts some such motion moves (for a large set: the motion described) and describes a
// motion they can make together: "it can rotate about (0, 2)", or per strut for a linkage,
// "'left' turns about (0, 0), 'top' slides along (1, 0) and 'right' turns about (3, 0),
// together".

#include <exception>
#include <functional>
#include <vector>

#include "scenes/frame_kinematics.hpp"

namespace fetic::scenes {

// Thrown when `stop` (asked before each set of struts) says to stop.
struct MechanismCheckStopped : std::exception {
  const char* what() const noexcept override { return "the mechanism check was interrupted"; }
};

std::vector<Mechanism> frame_mechanisms(const Scene& scene, const std::function<bool()>& stop = {});

}  // namespace fetic::scenes
