#include "solver/boundedness.hpp"

#include <cmath>
#include <vector>

namespace fetic::solver {
namespace {

struct Link {
  int other = -1;
  int pair = -1;
};

// Walks a path of struts from `start` (an end of the path) and returns it in order.
std::vector<int> walk_path(int start, const std::vector<std::vector<Link>>& links,
                           std::vector<char>& seen) {
  std::vector<int> path{start};
  seen[start] = 1;
  int current = start;
  while (true) {
    int next = -1;
    for (const Link& link : links[current])
      if (!seen[link.other]) next = link.other;
    if (next < 0) break;
    seen[next] = 1;
    path.push_back(next);
    current = next;
  }
  return path;
}

// Net axial load of a strut projected on the unit line direction v.
double load_along(const Model& model, int strut, const Vec2& v) {
  return model.loads[strut].sum() * model.struts[strut].e1.dot(v);
}

std::string escape_message(const Model& model, const std::vector<int>& struts, double load_factor) {
  std::string names;
  for (int s : struts)
    names += (names.empty() ? "'" : ", '") + model.strut_names[s] + "'";
  return "the scene is unbounded at load factor " + std::to_string(load_factor) + ": strut(s) " +
         names + " held by no support would be pushed away from every contact";
}

}  // namespace

std::string unbounded_struts(const Model& model, double load_factor) {
  if (model.dofs_per_node() != 1 || load_factor == 0.0) return {};
  const int count = static_cast<int>(model.struts.size());
  std::vector<std::vector<Link>> links(count);
  for (size_t k = 0; k < model.pairs.size(); ++k) {
    const ContactPair& pair = model.pairs[k];
    links[pair.strut_a].push_back({pair.strut_b, static_cast<int>(k)});
    links[pair.strut_b].push_back({pair.strut_a, static_cast<int>(k)});
  }
  std::vector<char> seen(count, 0);
  for (int s = 0; s < count; ++s) {
    if (seen[s] || links[s].size() > 1) continue;  // start walks at path ends
    const std::vector<int> path = walk_path(s, links, seen);
    // Line direction from the first strut toward the last.
    const Vec2 v = path.size() > 1
                       ? Vec2(model.struts[path.back()].origin - model.struts[path.front()].origin)
                             .normalized()
                       : model.struts[s].e1;
    double scale = 0.0;
    for (int strut : path)
      scale += std::abs(load_along(model, strut, v));
    const double tolerance = 1e-12 * scale;
    int first_clamped = -1, last_clamped = -1;
    for (size_t i = 0; i < path.size(); ++i)
      if (!model.floating(path[i])) {
        if (first_clamped < 0) first_clamped = static_cast<int>(i);
        last_clamped = static_cast<int>(i);
      }
    if (first_clamped < 0) continue;  // validation rejects such scenes
    // Free run before the first clamped strut escapes toward -v.
    double sum = 0.0;
    for (int i = 0; i < first_clamped; ++i) {
      sum += load_factor * load_along(model, path[i], v);
      if (sum < -tolerance * std::abs(load_factor))
        return escape_message(model, std::vector<int>(path.begin(), path.begin() + i + 1),
                              load_factor);
    }
    // Free run after the last clamped strut escapes toward +v.
    sum = 0.0;
    for (int i = static_cast<int>(path.size()) - 1; i > last_clamped; --i) {
      sum += load_factor * load_along(model, path[i], v);
      if (sum > tolerance * std::abs(load_factor))
        return escape_message(model, std::vector<int>(path.begin() + i, path.end()), load_factor);
    }
  }
  return {};
}

}  // namespace fetic::solver
