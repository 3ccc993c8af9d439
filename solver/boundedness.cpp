#include "solver/boundedness.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <vector>

#include <Eigen/Dense>

#include "scenes/union_find.hpp"

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

// min |M x - b| subject to x >= 0: Lawson and Hanson's active-set algorithm.
Eigen::VectorXd nonnegative_least_squares(const Eigen::MatrixXd& M, const Eigen::VectorXd& b) {
  const int n = static_cast<int>(M.cols());
  Eigen::VectorXd x = Eigen::VectorXd::Zero(n);
  std::vector<char> passive(n, 0);
  const double tolerance = 1e-13 * (M.cwiseAbs().maxCoeff() + 1e-300) * (b.norm() + 1e-300);
  for (int outer = 0; outer < 3 * n + 10; ++outer) {
    const Eigen::VectorXd w = M.transpose() * (b - M * x);
    int best = -1;
    double largest = tolerance;
    for (int j = 0; j < n; ++j)
      if (!passive[j] && w(j) > largest) {
        largest = w(j);
        best = j;
      }
    if (best < 0) break;
    passive[best] = 1;
    for (int inner = 0; inner < 3 * n + 10; ++inner) {
      std::vector<int> set;
      for (int j = 0; j < n; ++j)
        if (passive[j]) set.push_back(j);
      Eigen::MatrixXd Mp(M.rows(), static_cast<int>(set.size()));
      for (size_t i = 0; i < set.size(); ++i)
        Mp.col(static_cast<int>(i)) = M.col(set[i]);
      const Eigen::VectorXd zp = Mp.colPivHouseholderQr().solve(b);
      Eigen::VectorXd z = Eigen::VectorXd::Zero(n);
      for (size_t i = 0; i < set.size(); ++i)
        z(set[i]) = zp(static_cast<int>(i));
      double step = 1.0;
      for (int j : set)
        if (z(j) <= 0.0) step = std::min(step, x(j) / (x(j) - z(j)));
      x += step * (z - x);
      if (step >= 1.0) break;
      for (int j : set)
        if (x(j) <= 0.0) {
          x(j) = 0.0;
          passive[j] = 0;
        }
    }
  }
  return x;
}

// The free motions of a frame model (scenes/frame_kinematics), and what the loads and the
// contacts do along them.
struct FrameMotions {
  const Model& model;
  const scenes::FrameKinematics& kinematics = model.kinematics;
  const std::vector<scenes::FreeMotion>& motions = kinematics.motions;
  int k = static_cast<int>(motions.size());
  std::vector<std::vector<int>> motions_of = by_group();

  std::vector<std::vector<int>> by_group() const {
    std::vector<std::vector<int>> list(kinematics.groups.size());
    for (int m = 0; m < k; ++m)
      list[static_cast<size_t>(motions[m].group)].push_back(m);
    return list;
  }
  // Displacement and rotation of a node of a strut per unit of motion m.
  auto at(int m, int strut, int node) const {
    const Vec2& p = model.struts[strut].nodes[node];
    return scenes::motion_at(kinematics, motions[m], strut, {p.x(), p.y()});
  }
  // Work of the loads per unit of each motion; `load_scale` gets their size.
  Eigen::VectorXd load_work(double load_factor, double& load_scale) const {
    Eigen::VectorXd work = Eigen::VectorXd::Zero(k);
    load_scale = 0.0;
    for (size_t s = 0; s < model.struts.size(); ++s) {
      const Eigen::VectorXd& f = model.loads[s];
      load_scale += f.lpNorm<1>();
      for (int node = 0; node < model.struts[s].node_count(); ++node) {
        if (f.segment<3>(3 * node).isZero()) continue;
        for (int m : motions_of[kinematics.group_of_strut[s]]) {
          const auto u = at(m, static_cast<int>(s), node);
          work(m) +=
              load_factor * (f(3 * node) * u[0] + f(3 * node + 1) * u[1] + f(3 * node + 2) * u[2]);
        }
      }
    }
    return work;
  }
  // Change of a contact gap per unit of a motion of the two groups it touches (A Z).
  struct Entry {
    int pair, motion;
    double value;
  };
  // The entries of A Z; `sets` joins the motions that a contact changes together.
  std::vector<Entry> gap_changes(scenes::UnionFind& sets) const {
    std::vector<Entry> entries;
    for (int p = 0; p < static_cast<int>(model.pairs.size()); ++p) {
      const ContactPair& pair = model.pairs[p];
      const int ga = kinematics.group_of_strut[pair.strut_a];
      const int gb = kinematics.group_of_strut[pair.strut_b];
      std::vector<int> touched = motions_of[ga];
      if (gb != ga) touched.insert(touched.end(), motions_of[gb].begin(), motions_of[gb].end());
      int first = -1;
      for (int m : touched) {
        const auto ua = at(m, pair.strut_a, pair.node_a);
        const auto ub = at(m, pair.strut_b, pair.node_b);
        const double value = pair.normal.x() * (ua[0] - ub[0]) + pair.normal.y() * (ua[1] - ub[1]);
        if (std::abs(value) <= 1e-12) continue;
        entries.push_back({p, m, value});
        if (first < 0) first = m;
        sets.join(m, first);
      }
    }
    return entries;
  }
  // The struts that the combination `amount` of the motions `members` moves.
  std::vector<int> moved_struts(const std::vector<int>& members,
                                const Eigen::VectorXd& amount) const {
    std::vector<int> moved;
    std::vector<char> group_seen(kinematics.groups.size(), 0);
    for (int m : members) {
      const int g = motions[m].group;
      if (group_seen[g]) continue;
      group_seen[g] = 1;
      for (int s : kinematics.groups[g]) {
        double largest = 0.0;
        for (int node : {0, model.struts[s].nx}) {
          double ux = 0.0, uy = 0.0;
          for (size_t i = 0; i < members.size(); ++i) {
            if (motions[members[i]].group != g) continue;
            const auto u = at(members[i], s, node);
            ux += amount(static_cast<int>(i)) * u[0];
            uy += amount(static_cast<int>(i)) * u[1];
          }
          largest = std::max(largest, std::hypot(ux, uy));
        }
        if (largest > 1e-6 * amount.norm()) moved.push_back(s);
      }
    }
    std::sort(moved.begin(), moved.end());
    return moved;
  }
};

// Frame model: the loads' work along the free motions (scenes/frame_kinematics) must be
// balanced by compressive contact forces: Z'f = (A Z)' lambda for some lambda >= 0
// (Farkas), cluster by cluster of motions that contacts link. Otherwise the residual
// y = Z'f - (A Z)' lambda of the closest balance is a motion that opens every contact it
// touches ((A Z) y <= 0) and along which the loads do work: the struts it moves escape.
std::string frame_unbounded_struts(const Model& model, double load_factor) {
  const FrameMotions frame{model};
  const int k = frame.k;
  if (k == 0) return {};
  double load_scale = 0.0;
  const Eigen::VectorXd work = frame.load_work(load_factor, load_scale);
  scenes::UnionFind sets(k);
  const std::vector<FrameMotions::Entry> entries = frame.gap_changes(sets);
  std::vector<std::vector<int>> members_of(k), entries_of(k);
  for (int m = 0; m < k; ++m)
    members_of[sets.root(m)].push_back(m);
  for (size_t e = 0; e < entries.size(); ++e)
    entries_of[sets.root(entries[e].motion)].push_back(static_cast<int>(e));
  const double tolerance = 1e-10 * std::abs(load_factor) * load_scale;
  for (int cluster = 0; cluster < k; ++cluster) {
    const std::vector<int>& members = members_of[cluster];
    if (members.empty()) continue;
    std::vector<int> rows;
    std::map<int, int> row_of_pair, column_of_motion;
    for (size_t i = 0; i < members.size(); ++i)
      column_of_motion[members[i]] = static_cast<int>(i);
    for (int e : entries_of[cluster])
      if (row_of_pair.emplace(entries[e].pair, static_cast<int>(row_of_pair.size())).second)
        rows.push_back(entries[e].pair);
    const int n = static_cast<int>(members.size());
    Eigen::MatrixXd M = Eigen::MatrixXd::Zero(n, static_cast<int>(rows.size()));
    Eigen::VectorXd b(n);
    for (int i = 0; i < n; ++i)
      b(i) = work(members[i]);
    for (int e : entries_of[cluster])
      M(column_of_motion[entries[e].motion], row_of_pair[entries[e].pair]) = entries[e].value;
    const Eigen::VectorXd residual =
        rows.empty() ? b : Eigen::VectorXd(b - M * nonnegative_least_squares(M, b));
    if (!(residual.norm() > tolerance)) continue;
    return escape_message(model, frame.moved_struts(members, residual), load_factor);
  }
  return {};
}

}  // namespace

std::string unbounded_struts(const Model& model, double load_factor) {
  if (load_factor == 0.0) return {};
  if (model.frame()) return frame_unbounded_struts(model, load_factor);
  if (model.dofs_per_node() != 1) return {};
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
