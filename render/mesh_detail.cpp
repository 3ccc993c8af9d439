#include "render/mesh_detail.hpp"

#include <algorithm>
#include <cmath>

namespace fetic::render {
namespace {

// The part kept in detail: the visible rectangle widened by this share of its size on
// every side, so that panning by a quarter of the view does not rebuild.
constexpr double kKeepMargin = 0.25;

}  // namespace

bool WorldRect::contains(const WorldRect& other) const {
  return low.x() <= other.low.x() && low.y() <= other.low.y() && high.x() >= other.high.x() &&
         high.y() >= other.high.y();
}

bool WorldRect::overlaps(const WorldRect& other) const {
  return low.x() <= other.high.x() && other.low.x() <= high.x() && low.y() <= other.high.y() &&
         other.low.y() <= high.y();
}

WorldRect visible_world(const SceneFraming& f) {
  const double ppu = f.pixels_per_unit > 0.0 ? f.pixels_per_unit : 1.0;
  const auto world_x = [&](float px) { return f.world_center.x() + (px - f.pixel_center.x) / ppu; };
  const auto world_y = [&](float py) { return f.world_center.y() - (py - f.pixel_center.y) / ppu; };
  WorldRect r;
  r.low = solver::Vec2(world_x(f.region.x0), world_y(f.region.y1));
  r.high = solver::Vec2(world_x(f.region.x1), world_y(f.region.y0));
  return r;
}

int merge_stride(double element_pixels, int elements) {
  int stride = 1;
  while (stride < elements && stride * element_pixels < 1.0)
    stride *= 2;
  return std::min(stride, std::max(elements, 1));
}

std::vector<int> kept_nodes(int from, int to, int stride) {
  std::vector<int> kept;
  kept.reserve(static_cast<std::size_t>((to - from) / std::max(stride, 1) + 2));
  for (int x = from; x < to; x += std::max(stride, 1))
    kept.push_back(x);
  kept.push_back(to);
  return kept;
}

MeshDetail mesh_detail(const solver::Model& model, const SceneFraming& fitted,
                       const SceneFraming& placed, double cell_budget) {
  MeshDetail detail;
  const double zoom = placed.pixels_per_unit / fitted.pixels_per_unit;
  const double level = std::isfinite(zoom) && zoom > 0.0 ? std::floor(std::log2(zoom) + 1e-9) : 0.0;
  detail.pixels_per_unit = fitted.pixels_per_unit * std::exp2(level);
  double cells = 0.0;
  for (const solver::StrutMesh& strut : model.struts) {
    if (strut.dofs_per_node != 2) {
      cells += strut.nx;
      continue;
    }
    const double along = strut.length / strut.nx * detail.pixels_per_unit;
    const double across = strut.height / std::max(strut.ny, 1) * detail.pixels_per_unit;
    cells += std::ceil(double(strut.nx) / merge_stride(along, strut.nx)) *
             std::ceil(double(strut.ny) / merge_stride(across, strut.ny));
  }
  if (cells > cell_budget) {
    const WorldRect seen = visible_world(placed);
    const solver::Vec2 margin = kKeepMargin * (seen.high - seen.low);
    detail.keep.low = seen.low - margin;
    detail.keep.high = seen.high + margin;
  }
  return detail;
}

bool detail_serves(const MeshDetail& built, const MeshDetail& wanted, const SceneFraming& placed) {
  if (built.pixels_per_unit != wanted.pixels_per_unit) return false;
  return built.keep.contains(visible_world(placed));
}

}  // namespace fetic::render
