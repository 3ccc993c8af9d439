#pragma once
// Level of detail of a scene mesh: a picture is drawn at the screen's resolution, so plane
// elements smaller than a pixel are merged into cells of 2^a x 2^b elements (per piece,
// powers of two along and across, the smallest that makes a cell at least a pixel wide
// each way). A mesh is built for a level - the fit's scale times a power of two - and
// serves every zoom from that level up to the next, so panning and zooming within a
// level do not rebuild it. When the whole scene at that level would be too many cells,
// only the pieces near the visible part are kept in detail (the rest are one cell each)
// and the mesh serves while the view stays inside that part.

#include <limits>
#include <vector>

#include "render/scene_framing.hpp"
#include "solver/model.hpp"

namespace fetic::render {

struct WorldRect {
  solver::Vec2 low{-std::numeric_limits<double>::infinity(),
                   -std::numeric_limits<double>::infinity()};
  solver::Vec2 high{std::numeric_limits<double>::infinity(),
                    std::numeric_limits<double>::infinity()};
  bool contains(const WorldRect& other) const;
  bool overlaps(const WorldRect& other) const;
};

struct MeshDetail {
  double pixels_per_unit = 0.0;  // the level's scale; 0: every element as it is
  WorldRect keep;                // pieces outside it are drawn as one cell each
};

// The world rectangle a framing shows in its region.
WorldRect visible_world(const SceneFraming& framing);

// The detail for drawing `placed`, a zoom of the fitted framing `fitted` (the same
// framing for a picture that is not zoomed): its level and, when the scene at that level
// has more than a budget of cells, the visible rectangle widened by a quarter of its size
// on every side.
// A mesh of more cells than kCellBudget (about 200 MB of vertices) is kept in detail only
// near the visible part of the scene.
inline constexpr double kCellBudget = 1.0e6;
MeshDetail mesh_detail(const solver::Model& model, const SceneFraming& fitted,
                       const SceneFraming& placed, double cell_budget = kCellBudget);

// True when a mesh built with `built` can draw `placed` at the detail `wanted`: the same
// level, and the visible rectangle inside the part kept in detail.
bool detail_serves(const MeshDetail& built, const MeshDetail& wanted, const SceneFraming& placed);

// Elements merged per cell along one direction: the smallest power of two that makes a
// cell at least a pixel, at most `elements` (1 without a level).
int merge_stride(double element_pixels, int elements);

// The node indices a piece keeps from `from` to `to` with `stride`: from, from + stride,
// ..., and always `to`.
std::vector<int> kept_nodes(int from, int to, int stride);

}  // namespace fetic::render
