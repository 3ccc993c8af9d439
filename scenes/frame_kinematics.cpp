#include "scenes/frame_kinematics.hpp"
#include "scenes/frame_mechanisms.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <optional>
#include <unordered_map>

#include <Eigen/Dense>
#include <Eigen/SparseCore>

#include "scenes/null_space.hpp"
#include "scenes/scene_error.hpp"
#include "scenes/sparse_null_space.hpp"
#include "scenes/union_find.hpp"

#include "scenes/scene_geometry.hpp"

namespace fetic::scenes {
namespace {

std::string number_text(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.6g", std::abs(value) < 1e-12 ? 0.0 : value);
  return buffer;
}

// The rigid bodies of a set of struts - struts joined by rigid joints move as one; one
// with a clamped end does not move - and three parameters (a, b, phi = theta * size) per
// moving body, about the set's centre.
struct Bodies {
  std::unordered_map<int, int> local;  // strut -> index in the set
  std::vector<int> column;             // per index: its body's first column, -1: held
  int columns = 0;
  Point centre{0.0, 0.0};
  double size = 1.0;
};

Bodies make_bodies(const Scene& scene, const std::vector<int>& struts,
                   const std::vector<int>& joints) {
  Bodies bodies;
  const int count = static_cast<int>(struts.size());
  for (int i = 0; i < count; ++i)
    bodies.local[struts[i]] = i;
  UnionFind rigid(count);
  for (int j : joints)
    if (scene.joints[j].kind == JointKind::Rigid)
      for (const EndRef& end : scene.joints[j].ends)
        rigid.join(bodies.local.at(scene.joints[j].ends[0].strut), bodies.local.at(end.strut));
  std::vector<char> clamped(count, 0);
  for (int i = 0; i < count; ++i)
    if (scene.struts[struts[i]].clamped()) clamped[rigid.root(i)] = 1;
  std::vector<int> root_column(count, -1);
  for (int i = 0; i < count; ++i)
    if (rigid.root(i) == i && !clamped[i]) {
      root_column[i] = bodies.columns;
      bodies.columns += 3;
    }
  bodies.column.resize(count);
  for (int i = 0; i < count; ++i)
    bodies.column[i] = root_column[rigid.root(i)];
  for (int s : struts)
    for (Point p : {scene.struts[s].from, scene.struts[s].to}) {
      bodies.centre[0] += p[0] / (2.0 * count);
      bodies.centre[1] += p[1] / (2.0 * count);
    }
  double size = 0.0;
  for (int s : struts)
    for (Point p : {scene.struts[s].from, scene.struts[s].to})
      size = std::max(size, distance(p, bodies.centre));
  bodies.size = size > 0.0 ? size : 1.0;
  return bodies;
}

// Rows of the sparse constraint matrix: sum over the entries of (direction . u(p)).
class Rows {
 public:
  explicit Rows(const Bodies& bodies) : bodies_(bodies) {}
  // Adds d . u(p) of strut s (times sign) to the current row.
  void add(int strut, Point p, Point d, double sign) {
    const int c = bodies_.column[bodies_.local.at(strut)];
    if (c < 0) return;
    const double rx = -(p[1] - bodies_.centre[1]) / bodies_.size;
    const double ry = (p[0] - bodies_.centre[0]) / bodies_.size;
    push(c, sign * d[0]);
    push(c + 1, sign * d[1]);
    push(c + 2, sign * (d[0] * rx + d[1] * ry));
  }
  void end_row() {
    if (touched_) ++row_;
    touched_ = false;
  }
  Eigen::SparseMatrix<double> matrix() const {
    Eigen::SparseMatrix<double> A(row_, bodies_.columns);
    A.setFromTriplets(entries_.begin(), entries_.end());
    A.prune(0.0);  // a rigid joint's ends on one body cancel
    return A;
  }

 private:
  void push(int column, double value) {
    if (value == 0.0) return;
    entries_.emplace_back(row_, column, value);
    touched_ = true;
  }
  const Bodies& bodies_;
  std::vector<Eigen::Triplet<double>> entries_;
  int row_ = 0;
  bool touched_ = false;
};

// The constraints on the bodies' parameters: pinned supports hold their point, joints
// keep their ends together, contacts (when given) keep their gap.
Eigen::SparseMatrix<double> constraints(const Scene& scene, const Bodies& bodies,
                                        const std::vector<int>& struts,
                                        const std::vector<int>& joints,
                                        const std::vector<int>& contacts) {
  Rows rows(bodies);
  const Point ex{1.0, 0.0}, ey{0.0, 1.0};
  for (int s : struts)
    for (StrutEnd end : {StrutEnd::From, StrutEnd::To})
      if (scene.struts[s].pinned(end)) {
        const Point p = end_point(scene.struts[s], end);
        for (Point d : {ex, ey}) {
          rows.add(s, p, d, 1.0);
          rows.end_row();
        }
      }
  for (int j : joints) {
    const Joint& joint = scene.joints[j];
    const Point p = end_point(scene.struts[joint.ends[0].strut], joint.ends[0].end);
    for (size_t e = 1; e < joint.ends.size(); ++e)
      for (Point d : {ex, ey}) {
        rows.add(joint.ends[0].strut, p, d, 1.0);
        rows.add(joint.ends[e].strut, p, d, -1.0);
        rows.end_row();
      }
  }
  for (int c : contacts) {
    const Contact& contact = scene.contacts[c];
    const FrameContactGeometry g = frame_contact_geometry(scene, contact);
    rows.add(contact.a.strut, node_point(scene, contact.a), g.normal, 1.0);
    rows.add(contact.b.strut, node_point(scene, contact.b), g.normal, -1.0);
    rows.end_row();
  }
  return rows.matrix();
}

// The motion (a, b, theta) of strut s in the parameter vector z.
std::array<double, 3> strut_motion(const Bodies& bodies, const Eigen::VectorXd& z, int strut) {
  const int c = bodies.column[bodies.local.at(strut)];
  if (c < 0) return {0.0, 0.0, 0.0};
  return {z(c), z(c + 1), z(c + 2) / bodies.size};
}

// Displacement of point p under motion m about the centre c.
Point moved(const std::array<double, 3>& m, Point c, Point p) {
  return {m[0] - m[2] * (p[1] - c[1]), m[1] + m[2] * (p[0] - c[0])};
}

// "slide along (1, 0)" or "turn about (0, 2)": one strut's rigid motion.
std::string rigid_motion_text(const std::array<double, 3>& m, Point c, double size,
                              const std::string& slide, const std::string& turn) {
  const double shift = std::hypot(m[0], m[1]);
  if (std::abs(m[2]) * size <= 1e-6 * shift) {
    // The direction either way: written with a positive x (or, along y, a positive y).
    const double sign =
        m[0] > 1e-12 * shift || (std::abs(m[0]) <= 1e-12 * shift && m[1] > 0.0) ? 1.0 : -1.0;
    return slide + " along (" + number_text(sign * m[0] / shift) + ", " +
           number_text(sign * m[1] / shift) + ")";
  }
  return turn + " about (" + number_text(c[0] - m[1] / m[2]) + ", " +
         number_text(c[1] + m[0] / m[2]) + ")";
}

// One motion the struts make together: "it can rotate about (0, 0)" when all move as one
// body; else each (distinct) strut's own part, "'left' turns about (0, 0), 'top' slides
// along (1, 0) and 'right' turns about (3, 0), together".
std::string describe(const Scene& scene, const Bodies& bodies, const Eigen::VectorXd& z,
                     const std::vector<int>& struts) {
  std::vector<std::array<double, 3>> motions;
  double scale = 0.0;
  for (int s : struts) {
    motions.push_back(strut_motion(bodies, z, s));
    scale = std::max({scale, std::abs(motions.back()[0]), std::abs(motions.back()[1]),
                      std::abs(motions.back()[2]) * bodies.size});
  }
  auto same = [&](const std::array<double, 3>& a, const std::array<double, 3>& b) {
    return std::abs(a[0] - b[0]) + std::abs(a[1] - b[1]) + std::abs(a[2] - b[2]) * bodies.size <=
           1e-9 * scale;
  };
  bool one_body = true;
  for (const auto& m : motions)
    one_body = one_body && same(m, motions.front());
  if (one_body)
    return rigid_motion_text(motions.front(), bodies.centre, bodies.size,
                             struts.size() == 1 ? "it can slide" : "they can slide together",
                             struts.size() == 1 ? "it can rotate" : "they can rotate together");
  std::string text;
  const size_t shown = std::min<size_t>(struts.size(), 3);
  for (size_t i = 0; i < shown; ++i) {
    text += i == 0 ? "" : (i + 1 == shown && shown == struts.size() ? " and " : ", ");
    text += "'" + printable(scene.struts[struts[i]].name) + "' " +
            rigid_motion_text(motions[i], bodies.centre, bodies.size, "slides", "turns");
  }
  if (shown < struts.size()) text += " and " + std::to_string(struts.size() - shown) + " more move";
  return text + ", together";
}

// The struts some null vector (column of Z) moves, relative to the largest motion.
std::vector<int> moved_struts(const Scene& scene, const Bodies& bodies, const Eigen::MatrixXd& Z,
                              const std::vector<int>& struts) {
  std::vector<double> largest(struts.size(), 0.0);
  double overall = 0.0;
  for (int f = 0; f < Z.cols(); ++f)
    for (size_t i = 0; i < struts.size(); ++i) {
      const auto m = strut_motion(bodies, Z.col(f), struts[i]);
      for (Point p : {scene.struts[struts[i]].from, scene.struts[struts[i]].to}) {
        const Point u = moved(m, bodies.centre, p);
        largest[i] = std::max(largest[i], std::hypot(u[0], u[1]));
      }
      overall = std::max(overall, largest[i]);
    }
  std::vector<int> result;
  for (size_t i = 0; i < struts.size(); ++i)
    if (largest[i] > 1e-6 * overall && largest[i] > 0.0) result.push_back(struts[i]);
  return result;
}

// The mechanism of one set of struts that joints and contacts link, if any.
std::optional<Mechanism> set_mechanism(const Scene& scene, const std::vector<int>& struts,
                                       const std::vector<int>& joints,
                                       const std::vector<int>& contacts) {
  const Bodies bodies = make_bodies(scene, struts, joints);
  if (bodies.columns == 0) return std::nullopt;
  const Eigen::SparseMatrix<double> A = constraints(scene, bodies, struts, joints, contacts);
  // Small sets: every free motion (dense SVD); large ones: one, by sparse QR.
  const Eigen::MatrixXd Z = bodies.columns <= kSparseNullSpaceColumns
                                ? null_space(Eigen::MatrixXd(A), bodies.columns)
                                : sparse_null_space(A, 1);
  if (Z.cols() == 0) return std::nullopt;
  Mechanism mechanism;
  mechanism.struts = moved_struts(scene, bodies, Z, struts);
  if (mechanism.struts.empty()) return std::nullopt;
  // The motion described: the first free one, over the struts it moves itself.
  const std::vector<int> its = moved_struts(scene, bodies, Z.leftCols(1), struts);
  mechanism.motion = describe(scene, bodies, Z.col(0), its.empty() ? mechanism.struts : its);
  return mechanism;
}

// The free motions of one group of struts joined by joints: an orthonormal basis of the
// null space of its support and joint constraints (in the scaled parameters).
void group_motions(const Scene& scene, int group, const std::vector<int>& struts,
                   const std::vector<int>& joints, std::vector<FreeMotion>& motions) {
  const Bodies bodies = make_bodies(scene, struts, joints);
  if (bodies.columns == 0) return;
  const Eigen::SparseMatrix<double> C = constraints(scene, bodies, struts, joints, {});
  const Eigen::MatrixXd basis = bodies.columns <= kSparseNullSpaceColumns
                                    ? null_space(Eigen::MatrixXd(C), bodies.columns)
                                    : sparse_null_space(C);
  const int count = static_cast<int>(struts.size());
  for (int m = 0; m < basis.cols(); ++m) {
    FreeMotion motion;
    motion.group = group;
    motion.centre = bodies.centre;
    motion.of_strut.resize(count, {0.0, 0.0, 0.0});
    for (int i = 0; i < count; ++i) {
      const int column = bodies.column[i];
      if (column < 0) continue;
      motion.of_strut[i] = {basis(column, m), basis(column + 1, m),
                            basis(column + 2, m) / bodies.size};
    }
    motions.push_back(std::move(motion));
  }
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
  int group_count = 0;
  k.group_of_strut = joined.set_numbers(group_count);
  k.groups.resize(static_cast<size_t>(group_count));
  k.position_in_group.assign(n, -1);
  for (int s = 0; s < n; ++s) {
    std::vector<int>& group = k.groups[static_cast<size_t>(k.group_of_strut[s])];
    k.position_in_group[s] = static_cast<int>(group.size());
    group.push_back(s);
  }
  std::vector<std::vector<int>> joints_of(k.groups.size());
  for (size_t j = 0; j < scene.joints.size(); ++j)
    joints_of[k.group_of_strut[scene.joints[j].ends[0].strut]].push_back(static_cast<int>(j));
  for (size_t g = 0; g < k.groups.size(); ++g)
    group_motions(scene, static_cast<int>(g), k.groups[g], joints_of[g], k.motions);
  return k;
}

std::vector<Mechanism> frame_mechanisms(const Scene& scene, const std::function<bool()>& stop) {
  // Struts that joints or contacts link are judged together.
  const int n = static_cast<int>(scene.struts.size());
  UnionFind linked(n);
  for (const Joint& joint : scene.joints)
    for (const EndRef& end : joint.ends)
      linked.join(joint.ends[0].strut, end.strut);
  for (const Contact& contact : scene.contacts)
    linked.join(contact.a.strut, contact.b.strut);
  std::vector<std::vector<int>> struts_of(n), joints_of(n), contacts_of(n);
  for (int s = 0; s < n; ++s)
    struts_of[linked.root(s)].push_back(s);
  for (size_t j = 0; j < scene.joints.size(); ++j)
    joints_of[linked.root(scene.joints[j].ends[0].strut)].push_back(static_cast<int>(j));
  for (size_t c = 0; c < scene.contacts.size(); ++c)
    contacts_of[linked.root(scene.contacts[c].a.strut)].push_back(static_cast<int>(c));
  std::vector<Mechanism> mechanisms;
  for (int root = 0; root < n; ++root) {
    if (struts_of[root].empty()) continue;
    if (stop && stop()) throw MechanismCheckStopped();
    if (auto mechanism = set_mechanism(scene, struts_of[root], joints_of[root], contacts_of[root]))
      mechanisms.push_back(std::move(*mechanism));
  }
  return mechanisms;
}

std::vector<Mechanism> frame_mechanisms(const Scene& scene, const FrameKinematics&) {
  return frame_mechanisms(scene, std::function<bool()>());
}

}  // namespace fetic::scenes
