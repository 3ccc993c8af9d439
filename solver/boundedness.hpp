#pragma once
// Is a bar scene bounded at a load factor? Contacts only push, so a strut held by no
// support can be pushed away from every contact. Struts linked by contacts lie on one
// line and form a path (each end takes part in at most one contact); the struts beyond
// the last clamped strut of a path can all move outward freely, so the scene is
// unbounded exactly when some run of them at the free end of a path is pushed outward
// in total (Farkas: no compressive contact forces can then balance the loads).
// The plane model needs no such check: every plane strut is clamped. The frame model
// checks whether compressive contact forces can balance the loads' work along every
// free motion (boundedness.cpp, frame_unbounded_struts).

#include <string>

#include "solver/model.hpp"

namespace fetic::solver {

// Empty when bounded; otherwise the message naming the struts that escape.
std::string unbounded_struts(const Model& model, double load_factor);

}  // namespace fetic::solver
