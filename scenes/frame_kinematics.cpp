#include "scenes/frame_kinematics.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <unordered_map>

#include <Eigen/Dense>

#include "scenes/null_space.hpp"
#include "scenes/union_find.hpp"

#include "scenes/scene_geometry.hpp"

namespace fetic::scenes {
namespace {

std::string number_text(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.6g", std::abs(value) < 1e-12 ? 0.0 : value);
  return buffer;
}

// The free motions of one group of struts joined by joints.
void group_motions(const Scene& scene, int group, const std::vector<int>& struts,
                   const std::vector<int>& joints, std::vector<FreeMotion>& motions) {
  // Bodies: struts joined by rigid joints move as one.
  const int count = static_cast<int>(struts.size());
  std::unordered_map<int, int> local;  // strut -> index in the group
  for (int i = 0; i < count; ++i)
    local[struts[i]] = i;
  UnionFind rigid(count);
  for (int j : joints) {
    const Joint& joint = scene.joints[j];
    if (joint.kind != JointKind::Rigid) continue;
    for (const EndRef& end : joint.ends)
      rigid.join(local.at(joint.ends[0].strut), local.at(end.strut));
  }
  // A body with a clamped end does not move: it has no parameters.
  std::vector<char> clamped(count, 0);
  for (int i = 0; i < count; ++i)
    if (scene.struts[struts[i]].clamped()) clamped[rigid.root(i)] = 1;
  std::vector<int> body_column(count, -1);  // per root: first parameter column
  int columns = 0;
  for (int i = 0; i < count; ++i)
    if (rigid.root(i) == i && !clamped[i]) {
      body_column[i] = columns;
      columns += 3;
    }
  if (columns == 0) return;

  // Centre and size of the group: rotations are scaled by the size so that all
  // parameters are displacements of comparable magnitude.
  Point centre{0.0, 0.0};
  for (int s : struts)
    for (Point p : {scene.struts[s].from, scene.struts[s].to}) {
      centre[0] += p[0] / (2.0 * count);
      centre[1] += p[1] / (2.0 * count);
    }
  double size = 0.0;
  for (int s : struts)
    for (Point p : {scene.struts[s].from, scene.struts[s].to})
      size = std::max(size, distance(p, centre));
  if (!(size > 0.0)) size = 1.0;

  // Constraint rows on (a, b, phi = theta * size) of every moving body.
  std::vector<Eigen::RowVectorXd> rows;
  auto translation_rows = [&](int strut, Point p, double sign, Eigen::RowVectorXd& x,
                              Eigen::RowVectorXd& y) {
    const int column = body_column[rigid.root(local.at(strut))];
    if (column < 0) return;
    x(column) += sign;
    x(column + 2) -= sign * (p[1] - centre[1]) / size;
    y(column + 1) += sign;
    y(column + 2) += sign * (p[0] - centre[0]) / size;
  };
  auto add = [&](const Eigen::RowVectorXd& row) {
    if (row.cwiseAbs().maxCoeff() > 0.0) rows.push_back(row);
  };
  for (int s : struts) {
    const Strut& strut = scene.struts[s];
    for (StrutEnd end : {StrutEnd::From, StrutEnd::To}) {
      if (!strut.pinned(end)) continue;  // clamped struts have no parameters
      Eigen::RowVectorXd x = Eigen::RowVectorXd::Zero(columns), y = x;
      translation_rows(s, end_point(strut, end), 1.0, x, y);
      add(x);
      add(y);
    }
  }
  for (int j : joints) {
    const Joint& joint = scene.joints[j];
    const Point p = end_point(scene.struts[joint.ends[0].strut], joint.ends[0].end);
    for (size_t e = 1; e < joint.ends.size(); ++e) {
      Eigen::RowVectorXd x = Eigen::RowVectorXd::Zero(columns), y = x;
      translation_rows(joint.ends[0].strut, p, 1.0, x, y);
      translation_rows(joint.ends[e].strut, p, -1.0, x, y);
      add(x);
      add(y);
    }
  }
  Eigen::MatrixXd C(static_cast<int>(rows.size()), columns);
  for (size_t r = 0; r < rows.size(); ++r)
    C.row(static_cast<int>(r)) = rows[r];
  const Eigen::MatrixXd basis = null_space(C, columns);
  for (int m = 0; m < basis.cols(); ++m) {
    FreeMotion motion;
    motion.group = group;
    motion.centre = centre;
    motion.of_strut.resize(count, {0.0, 0.0, 0.0});
    for (int i = 0; i < count; ++i) {
      const int column = body_column[rigid.root(i)];
      if (column < 0) continue;
      motion.of_strut[i] = {basis(column, m), basis(column + 1, m), basis(column + 2, m) / size};
    }
    motions.push_back(std::move(motion));
  }
}

// Where a motion leaves the first strut it moves: a fixed point (rotation) or none
// (translation).
std::string describe(const Scene& scene, const FrameKinematics& k, const Eigen::VectorXd& y,
                     const std::vector<int>& motions, int strut) {
  double a = 0.0, b = 0.0, theta = 0.0;
  Point c{};
  for (size_t j = 0; j < motions.size(); ++j) {
    const FreeMotion& m = k.motions[motions[j]];
    if (m.group != k.group_of_strut[strut]) continue;
    const auto& v = m.of_strut[k.position_in_group[strut]];
    a += y(static_cast<int>(j)) * v[0];
    b += y(static_cast<int>(j)) * v[1];
    theta += y(static_cast<int>(j)) * v[2];
    c = m.centre;
  }
  const double size = std::max(length(scene.struts[strut]), 1e-300);
  const double shift = std::hypot(a, b);
  if (std::abs(theta) * size <= 1e-6 * shift) {
    // The direction either way: written with a positive x (or, along y, a positive y).
    const double sign = a > 1e-12 * shift || (std::abs(a) <= 1e-12 * shift && b > 0.0) ? 1.0 : -1.0;
    return "it can slide along (" + number_text(sign * a / shift) + ", " +
           number_text(sign * b / shift) + ")";
  }
  return "it can rotate about (" + number_text(c[0] - b / theta) + ", " +
         number_text(c[1] + a / theta) + ")";
}

}  // namespace

std::array<double, 3> motion_at(const FrameKinematics& kinematics, const FreeMotion& motion,
                                int strut, Point p) {
  if (kinematics.group_of_strut[strut] != motion.group) return {0.0, 0.0, 0.0};
  const auto& v = motion.of_strut[kinematics.position_in_group[strut]];
  return {v[0] - v[2] * (p[1] - motion.centre[1]), v[1] + v[2] * (p[0] - motion.centre[0]), v[2]};
}

FrameKinematics frame_kinematics(const Scene& scene) {
  FrameKinematics k;
  const int n = static_cast<int>(scene.struts.size());
  UnionFind joined(n);
  for (const Joint& joint : scene.joints)
    for (const EndRef& end : joint.ends)
      joined.join(joint.ends[0].strut, end.strut);
  k.group_of_strut.assign(n, -1);
  k.position_in_group.assign(n, -1);
  std::vector<int> group_of_root(n, -1);
  for (int s = 0; s < n; ++s) {
    int& group = group_of_root[joined.root(s)];
    if (group < 0) {
      group = static_cast<int>(k.groups.size());
      k.groups.emplace_back();
    }
    k.group_of_strut[s] = group;
    k.position_in_group[s] = static_cast<int>(k.groups[group].size());
    k.groups[group].push_back(s);
  }
  std::vector<std::vector<int>> joints_of(k.groups.size());
  for (size_t j = 0; j < scene.joints.size(); ++j)
    joints_of[k.group_of_strut[scene.joints[j].ends[0].strut]].push_back(static_cast<int>(j));
  for (size_t g = 0; g < k.groups.size(); ++g)
    group_motions(scene, static_cast<int>(g), k.groups[g], joints_of[g], k.motions);
  return k;
}

std::vector<Mechanism> frame_mechanisms(const Scene& scene, const FrameKinematics& k) {
  // Groups that contacts link are judged together.
  const int groups = static_cast<int>(k.groups.size());
  UnionFind linked(groups);
  for (const Contact& contact : scene.contacts)
    linked.join(k.group_of_strut[contact.a.strut], k.group_of_strut[contact.b.strut]);
  std::vector<std::vector<int>> motions_of(groups), contacts_of(groups), struts_of(groups);
  for (size_t s = 0; s < scene.struts.size(); ++s)
    struts_of[linked.root(k.group_of_strut[s])].push_back(static_cast<int>(s));
  for (size_t m = 0; m < k.motions.size(); ++m)
    motions_of[linked.root(k.motions[m].group)].push_back(static_cast<int>(m));
  for (size_t c = 0; c < scene.contacts.size(); ++c)
    contacts_of[linked.root(k.group_of_strut[scene.contacts[c].a.strut])].push_back(
        static_cast<int>(c));

  std::vector<Mechanism> mechanisms;
  for (int root = 0; root < groups; ++root) {
    const std::vector<int>& motions = motions_of[root];
    if (motions.empty()) continue;
    const int cols = static_cast<int>(motions.size());
    // Change of each contact's gap per unit of each motion.
    Eigen::MatrixXd M(static_cast<int>(contacts_of[root].size()), cols);
    for (size_t r = 0; r < contacts_of[root].size(); ++r) {
      const Contact& contact = scene.contacts[contacts_of[root][r]];
      const FrameContactGeometry g = frame_contact_geometry(scene, contact);
      const Point pa = node_point(scene, contact.a), pb = node_point(scene, contact.b);
      for (int j = 0; j < cols; ++j) {
        const FreeMotion& motion = k.motions[motions[j]];
        const auto ua = motion_at(k, motion, contact.a.strut, pa);
        const auto ub = motion_at(k, motion, contact.b.strut, pb);
        M(static_cast<int>(r), j) = g.normal[0] * (ua[0] - ub[0]) + g.normal[1] * (ua[1] - ub[1]);
      }
    }
    const Eigen::MatrixXd free = null_space(M, cols);
    if (free.cols() == 0) continue;
    // Struts any unheld motion moves.
    Mechanism mechanism;
    for (int s : struts_of[root]) {
      double largest = 0.0;
      for (int f = 0; f < free.cols(); ++f)
        for (Point p : {scene.struts[s].from, scene.struts[s].to}) {
          double ux = 0.0, uy = 0.0;
          for (int j = 0; j < cols; ++j) {
            const auto u = motion_at(k, k.motions[motions[j]], s, p);
            ux += free(j, f) * u[0];
            uy += free(j, f) * u[1];
          }
          largest = std::max(largest, std::hypot(ux, uy));
        }
      if (largest > 1e-6) mechanism.struts.push_back(s);
    }
    if (mechanism.struts.empty()) continue;
    mechanism.motion = describe(scene, k, free.col(0), motions, mechanism.struts.front());
    mechanisms.push_back(std::move(mechanism));
  }
  return mechanisms;
}

}  // namespace fetic::scenes
