#include "solver/feti_preconditioner.hpp"

#include <algorithm>
#include <map>

namespace fetic::solver {
namespace {

// The submatrix K(rows, cols) for sorted index lists given as position maps (-1: absent).
SparseMatrix extract(const SparseMatrix& K, const std::vector<int>& row_position, int rows,
                     const std::vector<int>& col_position, int cols) {
  std::vector<Eigen::Triplet<double>> entries;
  for (int col = 0; col < K.outerSize(); ++col) {
    if (col_position[col] < 0) continue;
    for (SparseMatrix::InnerIterator it(K, col); it; ++it)
      if (row_position[it.row()] >= 0)
        entries.emplace_back(row_position[it.row()], col_position[col], it.value());
  }
  SparseMatrix S(rows, cols);
  S.setFromTriplets(entries.begin(), entries.end());
  return S;
}

}  // namespace

FetiPreconditioner::FetiPreconditioner(const FetiSystem& system, Preconditioner kind, bool scaled)
    : system_(system), kind_(kind) {
  if (kind_ == Preconditioner::None) return;
  const Decomposition& d = system.decomposition();
  const auto& ops = system.subdomains();
  const int count = static_cast<int>(ops.size());

  // Per-entry weights of B (stiffness scaling): an entry of subdomain i in a row shared
  // with subdomain j gets k_j / (sum of k over every copy of the DOF), k the diagonal
  // stiffness: 1/multiplicity between equal neighbours.
  std::vector<std::map<int, double>> weight(d.row_count());  // row -> subdomain -> weight
  auto stiffness = [&](const RowEntry& entry) {
    return ops[entry.subdomain].K.coeff(entry.dof, entry.dof);
  };
  for (int r = 0; r < d.row_count(); ++r) {
    const Row& row = d.rows[r];
    for (const RowEntry& entry : row.entries)
      weight[r][entry.subdomain] = 1.0;
    // Largest diagonal stiffness per side (a plane contact row has two entries a side).
    std::map<int, double> side;
    for (const RowEntry& entry : row.entries)
      side[entry.subdomain] = std::max(side[entry.subdomain], stiffness(entry));
    if (!scaled || side.size() < 2) continue;
    double total = 0.0;
    if (row.copies.empty())
      for (const auto& [sub, k] : side)
        total += k;
    else
      for (const RowEntry& copy : row.copies)
        total += stiffness(copy);
    if (!(total > 0.0)) continue;
    for (const auto& [sub, k] : side) {
      double others = 0.0;
      for (const auto& [other, k_other] : side)
        if (other != sub) others += k_other;
      weight[r][sub] = others / total;
    }
  }

  local_.resize(count);
  row_entries_.assign(d.row_count(), {});
  int offset = 0;
  for (int j = 0; j < count; ++j) {
    Local& local = local_[j];
    const SubdomainOperator& op = ops[j];
    for (const Incidence& in : op.incidence)
      local.boundary.push_back(in.dof);
    std::sort(local.boundary.begin(), local.boundary.end());
    local.boundary.erase(std::unique(local.boundary.begin(), local.boundary.end()),
                         local.boundary.end());
    const int n = static_cast<int>(op.K.rows());
    const int nb = static_cast<int>(local.boundary.size());
    std::vector<int> b_position(n, -1), i_position(n, -1);
    for (int p = 0; p < nb; ++p)
      b_position[local.boundary[p]] = p;
    int ni = 0;
    for (int dof = 0; dof < n; ++dof)
      if (b_position[dof] < 0) i_position[dof] = ni++;
    for (const Incidence& in : op.incidence) {
      row_entries_[in.row].emplace_back(j, static_cast<int>(local.incidence.size()));
      local.incidence.push_back({in.row, b_position[in.dof], in.value * weight[in.row][j]});
    }
    local.K_bb = extract(op.K, b_position, nb, b_position, nb);
    if (kind_ == Preconditioner::Dirichlet && ni > 0) {
      local.K_ib = extract(op.K, i_position, ni, b_position, nb);
      const SparseMatrix K_ii = extract(op.K, i_position, ni, i_position, ni);
      if (local.K_ii.factorize(K_ii) != CholmodFactor::Result::Ok)
        throw SolverError("Dirichlet preconditioner: the interior of a subdomain of strut '" +
                          system.model().strut_names[d.subdomains[j].strut] + "' is singular");
    }
    local.offset = offset;
    offset += nb;
  }
  x_.resize(offset);
  y_.resize(offset);
}

std::size_t FetiPreconditioner::factor_memory() const {
  std::size_t total = 0;
  for (const Local& local : local_)
    total += local.K_ii.peak_memory();
  return total;
}

void FetiPreconditioner::apply(const Eigen::VectorXd& w, const std::vector<char>* mask,
                               Eigen::VectorXd& z) const {
  const int rows = static_cast<int>(w.size());
  if (kind_ == Preconditioner::None) {
    z = w;
    if (mask)
      for (int r = 0; r < rows; ++r)
        if (!(*mask)[r]) z(r) = 0.0;
    return;
  }
  const int count = static_cast<int>(local_.size());
#pragma omp parallel for schedule(dynamic, 4)
  for (int j = 0; j < count; ++j) {
    const Local& local = local_[j];
    const int nb = static_cast<int>(local.boundary.size());
    auto x = x_.segment(local.offset, nb);
    auto y = y_.segment(local.offset, nb);
    x.setZero();
    for (const Incidence& in : local.incidence)
      if (!mask || (*mask)[in.row]) x(in.dof) += in.value * w(in.row);
    y = local.K_bb * x;
    if (local.K_ii.size() > 0) {
      Eigen::VectorXd interior_rhs = local.K_ib * x;
      Eigen::VectorXd interior(interior_rhs.size());
      local.K_ii.solve(interior_rhs.data(), interior.data());
      y -= local.K_ib.transpose() * interior;
    }
  }
  z.resize(rows);
#pragma omp parallel for schedule(static)
  for (int r = 0; r < rows; ++r) {
    double sum = 0.0;
    if (!mask || (*mask)[r])
      for (const auto& [j, e] : row_entries_[r]) {
        const Incidence& in = local_[j].incidence[e];
        sum += in.value * y_(local_[j].offset + in.dof);
      }
    z(r) = sum;
  }
}

}  // namespace fetic::solver
