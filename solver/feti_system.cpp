#include "solver/feti_system.hpp"

#include <algorithm>
#include <atomic>
#include <string>

#include "solver/primal_problem.hpp"
#include "solver/rigid_modes.hpp"

namespace fetic::solver {
namespace {

constexpr double kSingularRcond = 1e-15;

}  // namespace

FetiSystem::FetiSystem(const Model& model)
    : model_(model), decomposition_(decompose(model)), space_(decomposition_) {
  const int count = static_cast<int>(decomposition_.subdomains.size());
  subdomains_.resize(count);
  for (int r = 0; r < decomposition_.row_count(); ++r)
    for (const RowEntry& entry : decomposition_.rows[r].entries)
      subdomains_[entry.subdomain].incidence.push_back({r, entry.dof, entry.value});

  std::vector<CholmodFactor::Result> results(count, CholmodFactor::Result::Ok);
  std::vector<char> singular(count, 0);
#pragma omp parallel for schedule(dynamic)
  for (int j = 0; j < count; ++j) {
    const Subdomain& sub = decomposition_.subdomains[j];
    const StrutMesh& mesh = model.struts[sub.strut];
    SubdomainOperator& op = subdomains_[j];
    op.K = assemble_stiffness(mesh, sub.box);
    op.R = rigid_body_modes(mesh, sub.box);
    results[j] = op.K_plus.factorize(op.K, op.R);
    singular[j] = results[j] == CholmodFactor::Result::Ok && op.K_plus.rcond() < kSingularRcond;
  }
  for (int j = 0; j < count; ++j) {
    if (results[j] == CholmodFactor::Result::Ok && !singular[j]) continue;
    const Subdomain& sub = decomposition_.subdomains[j];
    throw SolverError(singular_message(model, sub.strut, results[j],
                                       "its subdomain at nodes " + std::to_string(sub.box.i0) +
                                           ".." + std::to_string(sub.box.i1)));
  }

  c_ = Eigen::VectorXd::Zero(decomposition_.row_count());
  for (int r = 0; r < decomposition_.row_count(); ++r)
    c_(r) = decomposition_.rows[r].rhs;

  std::vector<Eigen::Triplet<double>> g_entries;
  for (int j = 0; j < count; ++j) {
    const Subdomain& sub = decomposition_.subdomains[j];
    const SubdomainOperator& op = subdomains_[j];
    for (const Incidence& in : op.incidence)
      for (int m = 0; m < sub.mode_count; ++m)
        if (op.R(in.dof, m) != 0.0)
          g_entries.emplace_back(sub.mode_offset + m, in.row, op.R(in.dof, m) * in.value);
  }
  G_.resize(decomposition_.total_modes, decomposition_.row_count());
  G_.setFromTriplets(g_entries.begin(), g_entries.end());
  x_.resize(decomposition_.total_dofs);
  y_.resize(decomposition_.total_dofs);
}

void FetiSystem::solve_subdomains(const Eigen::VectorXd* lambda, double s,
                                  double load_factor) const {
  const int count = static_cast<int>(subdomains_.size());
#pragma omp parallel for schedule(dynamic, 4)
  for (int j = 0; j < count; ++j) {
    const Subdomain& sub = decomposition_.subdomains[j];
    const SubdomainOperator& op = subdomains_[j];
    auto x = x_.segment(sub.dof_offset, sub.dof_count);
    if (load_factor != 0.0)
      x = load_factor * sub.load;
    else
      x.setZero();
    if (lambda)
      for (const Incidence& in : op.incidence)
        x(in.dof) += s * in.value * (*lambda)(in.row);
    op.K_plus.apply(x_.data() + sub.dof_offset, y_.data() + sub.dof_offset);
  }
}

void FetiSystem::gather_rows(Eigen::VectorXd& out) const {
  const int rows = decomposition_.row_count();
  out.resize(rows);
#pragma omp parallel for schedule(static)
  for (int r = 0; r < rows; ++r) {
    double sum = 0.0;
    for (const RowEntry& entry : decomposition_.rows[r].entries)
      sum += entry.value * y_(decomposition_.subdomains[entry.subdomain].dof_offset + entry.dof);
    out(r) = sum;
  }
}

void FetiSystem::residual(const Eigen::VectorXd& lambda, double load_factor,
                          Eigen::VectorXd& out) const {
  ++f_applications_;
  solve_subdomains(&lambda, -1.0, load_factor);
  gather_rows(out);
  out -= c_;
}

void FetiSystem::apply_F(const Eigen::VectorXd& p, Eigen::VectorXd& out) const {
  ++f_applications_;
  solve_subdomains(&p, 1.0, 0.0);
  gather_rows(out);
}

Eigen::VectorXd FetiSystem::d(double load_factor) const {
  solve_subdomains(nullptr, 0.0, load_factor);
  Eigen::VectorXd out;
  gather_rows(out);
  return out - c_;
}

Eigen::VectorXd FetiSystem::e(double load_factor) const {
  Eigen::VectorXd e = Eigen::VectorXd::Zero(decomposition_.total_modes);
  for (size_t j = 0; j < subdomains_.size(); ++j) {
    const Subdomain& sub = decomposition_.subdomains[j];
    e.segment(sub.mode_offset, sub.mode_count) =
        load_factor * (subdomains_[j].R.transpose() * sub.load);
  }
  return e;
}

Eigen::VectorXd FetiSystem::subdomain_displacements(const Eigen::VectorXd& lambda,
                                                    const Eigen::VectorXd& alpha,
                                                    double load_factor) const {
  solve_subdomains(&lambda, -1.0, load_factor);
  Eigen::VectorXd u = y_;
  for (size_t j = 0; j < subdomains_.size(); ++j) {
    const Subdomain& sub = decomposition_.subdomains[j];
    u.segment(sub.dof_offset, sub.dof_count) +=
        subdomains_[j].R * alpha.segment(sub.mode_offset, sub.mode_count);
  }
  return u;
}

std::vector<Piece> FetiSystem::pieces(const Eigen::VectorXd& lambda, const Eigen::VectorXd& alpha,
                                      double load_factor) const {
  const Eigen::VectorXd u = subdomain_displacements(lambda, alpha, load_factor);
  std::vector<Piece> result;
  result.reserve(subdomains_.size());
  for (const Subdomain& sub : decomposition_.subdomains) {
    const StrutMesh& mesh = model_.struts[sub.strut];
    Piece piece;
    piece.strut = sub.strut;
    piece.box = sub.box;
    piece.displacement.reserve(sub.box.node_count());
    for (int n = 0; n < sub.box.node_count(); ++n)
      piece.displacement.push_back(
          node_displacement(mesh, u.data() + sub.dof_offset + n * mesh.dofs_per_node));
    result.push_back(std::move(piece));
  }
  return result;
}

void FetiSystem::project_onto_range_of_B(Eigen::VectorXd& v) const {
  for (const RedundantGroup& group : decomposition_.redundant_groups) {
    double copy_sum[64];  // B_g' v_g per copy (a node has at most four copies)
    const int m = std::min(group.copies, 64);
    std::fill(copy_sum, copy_sum + m, 0.0);
    for (size_t k = 0; k < group.rows.size(); ++k) {
      copy_sum[group.ends[k].first] += v(group.rows[k]);
      copy_sum[group.ends[k].second] -= v(group.rows[k]);
    }
    for (size_t k = 0; k < group.rows.size(); ++k)
      v(group.rows[k]) = (copy_sum[group.ends[k].first] - copy_sum[group.ends[k].second]) / m;
  }
}

std::size_t FetiSystem::factor_memory() const {
  std::size_t total = 0;
  for (const SubdomainOperator& op : subdomains_)
    total += op.K_plus.peak_memory();
  return total;
}

}  // namespace fetic::solver
