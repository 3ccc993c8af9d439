#include "solver/free_motion_space.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

#include <Eigen/Dense>

#include "scenes/null_space.hpp"
#include "scenes/union_find.hpp"
#include "solver/corners.hpp"
#include "solver/rigid_modes.hpp"

namespace fetic::solver {
namespace {

// Entries below this (relative to a unit motion) are rounding.
constexpr double kNegligible = 1e-12;

// The subdomains of each group of struts (model.kinematics.groups).
std::vector<std::vector<int>> subdomains_by_group(const Model& model, const Decomposition& d) {
  std::vector<std::vector<int>> subdomains_of(model.kinematics.groups.size());
  for (size_t j = 0; j < d.subdomains.size(); ++j)
    subdomains_of[model.kinematics.group_of_strut[d.subdomains[j].strut]].push_back(
        static_cast<int>(j));
  return subdomains_of;
}

// Z (modes x motions): every free motion as amplitudes of the rigid modes of its group's
// subdomains.
Eigen::SparseMatrix<double> motion_amplitudes(const Model& model, const Decomposition& d,
                                              const std::vector<std::vector<int>>& subdomains_of) {
  const auto& motions = model.kinematics.motions;
  const int k = static_cast<int>(motions.size());
  std::vector<Eigen::Triplet<double>> entries;
  for (int m = 0; m < k; ++m) {
    for (int j : subdomains_of[motions[m].group]) {
      const Subdomain& sub = d.subdomains[j];
      const std::vector<SubdomainPart> parts = parts_of(sub, j);
      // The motion as amplitudes of each box's modes, then of the subdomain's.
      Eigen::VectorXd amplitudes(3 * parts.size());
      for (size_t p = 0; p < parts.size(); ++p) {
        const Vec2 c = box_centre(model.struts[parts[p].strut], parts[p].box);
        const auto u =
            scenes::motion_at(model.kinematics, motions[m], parts[p].strut, {c.x(), c.y()});
        amplitudes.segment<3>(3 * p) << u[2], u[0], u[1];  // the order of rigid_body_modes
      }
      const Eigen::VectorXd values =
          sub.parts.empty()
              ? amplitudes
              : Eigen::VectorXd(sub.part_modes.colPivHouseholderQr().solve(amplitudes));
      for (int i = 0; i < sub.mode_count; ++i)
        if (values(i) != 0.0) entries.emplace_back(sub.mode_offset + i, m, values(i));
    }
  }
  Eigen::SparseMatrix<double> Z(d.total_modes, k);
  Z.setFromTriplets(entries.begin(), entries.end());
  return Z;
}

// G'Z (contact rows x motions).
Eigen::SparseMatrix<double, Eigen::RowMajor> row_changes(const Model& model, const Decomposition& d,
                                                         const Eigen::SparseMatrix<double>& Z) {
  const auto& motions = model.kinematics.motions;
  const int k = static_cast<int>(motions.size());
  // (G'Z)(r, m) = sum over row r's entries of value * (R_j Z_j)(dof, m): the change of
  // contact row r per unit of motion m. From the replicated decomposition and the rigid
  // modes of the subdomains contact rows touch, not from G, whose columns a process
  // holds only for its own rows - so every process finds the same motions.
  // Per subdomain only the motions of its strut's group: a dense R_j Z_j over all motions
  // was quadratic (1,000 floating beams: 3,000 motions times 9,000 subdomains).
  std::vector<std::vector<int>> motions_of_group(model.kinematics.groups.size());
  for (int m = 0; m < k; ++m)
    motions_of_group[motions[m].group].push_back(m);
  const Eigen::SparseMatrix<double, Eigen::RowMajor> Z_rows = Z;
  const int first_contact = d.equality_rows;
  std::vector<Eigen::Triplet<double>> gz;
  std::vector<Eigen::MatrixXd> modes_of(d.subdomains.size());  // R_j Z_j, when needed
  for (int r = first_contact; r < d.row_count(); ++r)
    for (const RowEntry& entry : d.rows[r].entries) {
      const Subdomain& sub = d.subdomains[entry.subdomain];
      const std::vector<int>& moving = motions_of_group[model.kinematics.group_of_strut[sub.strut]];
      Eigen::MatrixXd& RZ = modes_of[entry.subdomain];
      if (RZ.size() == 0) {
        Eigen::MatrixXd Zj = Eigen::MatrixXd::Zero(sub.mode_count, static_cast<int>(moving.size()));
        for (int i = 0; i < sub.mode_count; ++i)
          for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(Z_rows,
                                                                              sub.mode_offset + i);
               it; ++it) {
            const auto at = std::lower_bound(moving.begin(), moving.end(), it.col());
            if (at != moving.end() && *at == it.col()) Zj(i, at - moving.begin()) = it.value();
          }
        RZ = subdomain_modes(model, sub) * Zj;
      }
      for (int c = 0; c < static_cast<int>(moving.size()); ++c)
        if (RZ(entry.dof, c) != 0.0)
          gz.emplace_back(r - first_contact, moving[c], entry.value * RZ(entry.dof, c));
    }
  Eigen::SparseMatrix<double, Eigen::RowMajor> GZ(d.contact_rows(), k);
  GZ.setFromTriplets(gz.begin(), gz.end());
  return GZ;
}

}  // namespace

FreeMotionSpace::FreeMotionSpace(const FetiSystem& system) : system_(system) {
  const Model& model = system.model();
  const Decomposition& d = system.decomposition();
  const auto& motions = model.kinematics.motions;
  const int k = static_cast<int>(motions.size());
  const std::vector<std::vector<int>> subdomains_of = subdomains_by_group(model, d);
  Z_ = motion_amplitudes(model, d, subdomains_of);
  GZ_ = row_changes(model, d, Z_);

  // Clusters: motions that a contact row changes together.
  scenes::UnionFind sets(k);
  const auto root = [&](int i) { return sets.root(i); };
  std::vector<std::vector<int>> row_motions(d.contact_rows());
  for (int r = 0; r < d.contact_rows(); ++r) {
    for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(GZ_, r); it; ++it)
      if (std::abs(it.value()) > kNegligible) row_motions[r].push_back(static_cast<int>(it.col()));
    for (int m : row_motions[r])
      sets.join(m, row_motions[r].front());
  }
  std::vector<int> cluster_of(k, -1);
  for (int m = 0; m < k; ++m) {
    int& c = cluster_of[root(m)];
    if (c < 0) {
      c = static_cast<int>(clusters_.size());
      clusters_.emplace_back();
    }
    clusters_[c].motions.push_back(m);
  }
  for (int r = 0; r < d.contact_rows(); ++r)
    if (!row_motions[r].empty())
      clusters_[cluster_of[root(row_motions[r].front())]].rows.push_back(r);
  for (Cluster& cluster : clusters_) {
    for (int m : cluster.motions)
      for (Eigen::SparseMatrix<double>::InnerIterator it(Z_, m); it; ++it)
        cluster.modes.push_back(static_cast<int>(it.row()));
    for (int m : cluster.motions)
      for (int j : subdomains_of[motions[m].group])
        cluster.subdomains.push_back(j);
    std::sort(cluster.subdomains.begin(), cluster.subdomains.end());
    cluster.subdomains.erase(std::unique(cluster.subdomains.begin(), cluster.subdomains.end()),
                             cluster.subdomains.end());
    std::sort(cluster.modes.begin(), cluster.modes.end());
    cluster.modes.erase(std::unique(cluster.modes.begin(), cluster.modes.end()),
                        cluster.modes.end());
  }
}

std::vector<UnheldGroup> FreeMotionSpace::unheld(const std::vector<char>& active) const {
  const Decomposition& d = system_.decomposition();
  if (static_cast<int>(active.size()) != d.contact_rows())
    throw std::logic_error("FreeMotionSpace: one flag per contact row expected");
  std::vector<UnheldGroup> groups;
  for (const Cluster& cluster : clusters_) {
    const int k = static_cast<int>(cluster.motions.size());
    std::vector<int> rows;
    for (int r : cluster.rows)
      if (active[r]) rows.push_back(r);
    Eigen::MatrixXd M = Eigen::MatrixXd::Zero(static_cast<int>(rows.size()), k);
    for (size_t i = 0; i < rows.size(); ++i)
      for (int j = 0; j < k; ++j)
        M(static_cast<int>(i), j) = GZ_.coeff(rows[i], cluster.motions[j]);
    const Eigen::MatrixXd N = scenes::null_space(M, static_cast<int>(M.cols()));
    if (N.cols() == 0) continue;
    // The free directions over the cluster's modes, orthonormalized.
    const int n = static_cast<int>(cluster.modes.size());
    Eigen::MatrixXd Zc = Eigen::MatrixXd::Zero(n, k);
    for (int j = 0; j < k; ++j)
      for (Eigen::SparseMatrix<double>::InnerIterator it(Z_, cluster.motions[j]); it; ++it) {
        const auto at = std::lower_bound(cluster.modes.begin(), cluster.modes.end(), it.row());
        Zc(static_cast<int>(at - cluster.modes.begin()), j) = it.value();
      }
    const Eigen::MatrixXd D = Zc * N;
    const Eigen::HouseholderQR<Eigen::MatrixXd> qr(D);
    const Eigen::MatrixXd Q = qr.householderQ() * Eigen::MatrixXd::Identity(n, D.cols());
    for (int c = 0; c < Q.cols(); ++c) {
      UnheldGroup group;
      group.direction.resize(d.total_modes);
      group.direction.reserve(n);
      for (int i = 0; i < n; ++i)  // cluster.modes increase
        if (Q(i, c) != 0.0) group.direction.insertBack(cluster.modes[i]) = Q(i, c);
      for (int j : cluster.subdomains) {
        const Subdomain& sub = d.subdomains[j];
        double largest = 0.0;
        for (auto at =
                 std::lower_bound(cluster.modes.begin(), cluster.modes.end(), sub.mode_offset);
             at != cluster.modes.end() && *at < sub.mode_offset + sub.mode_count; ++at)
          largest = std::max(largest, std::abs(Q(static_cast<int>(at - cluster.modes.begin()), c)));
        if (largest > kNegligible) group.subdomains.push_back(j);
      }
      groups.push_back(std::move(group));
    }
  }
  return groups;
}

}  // namespace fetic::solver
