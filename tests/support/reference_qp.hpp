#pragma once
// An independent reference for every contact scene: the primal QP
//   minimize 1/2 u'K u - t f'u  subject to  (u_a - u_b) . n <= gap  (each node pair)
// assembled here again straight from SCENES.md (no solver code is shared), split into
// the groups of struts that contacts connect (independent QPs), and solved exactly by
// CGAL's QP solver in exact arithmetic (Gmpzf).

#include <array>
#include <vector>

#include "scenes/scene.hpp"

namespace fetic::testing {

struct ReferenceSolution {
  bool optimal = false;
  // Per strut, per node (numbered along the strut, then across), (ux, uy).
  std::vector<std::vector<std::array<double, 2>>> displacement;
  // Frame model: per strut, per node, the rotation.
  std::vector<std::vector<double>> rotation;
  // Per contact node pair, in scene order: the contact force (KKT multiplier).
  std::vector<double> force;
};

ReferenceSolution solve_reference_qp(const scenes::Scene& scene, double load_factor);

}  // namespace fetic::testing
