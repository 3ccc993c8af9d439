#include "solver/coarse_problem.hpp"

#include <cmath>
#include <queue>
#include <stdexcept>

#include "solver/free_motion_space.hpp"

namespace fetic::solver {

CoarseProblem::CoarseProblem(const FetiSystem& system) : system_(system) {
  if (system.model().frame()) frame_motions_ = std::make_shared<const FreeMotionSpace>(system);
}

void CoarseProblem::set_active_rows(const std::vector<char>& active) {
  active_ = active;
  const SparseMatrix& G = system_.G();
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(static_cast<size_t>(G.nonZeros()));
  for (int col = 0; col < G.outerSize(); ++col) {
    if (!active_[col]) continue;
    for (SparseMatrix::InnerIterator it(G, col); it; ++it)
      entries.emplace_back(it.row(), col, it.value());
  }
  G_hat_.resize(G.rows(), G.cols());
  G_hat_.setFromTriplets(entries.begin(), entries.end());

  find_unheld_groups();
  SparseMatrix A = G_hat_ * SparseMatrix(G_hat_.transpose());
  if (!unheld_.empty()) {
    std::vector<Eigen::Triplet<double>> extra;
    for (const UnheldGroup& group : unheld_) {
      const Eigen::VectorXd& z = group.direction;
      for (int a : group.subdomains)
        for (int b : group.subdomains) {
          const Subdomain& sa = system_.decomposition().subdomains[a];
          const Subdomain& sb = system_.decomposition().subdomains[b];
          for (int ma = sa.mode_offset; ma < sa.mode_offset + sa.mode_count; ++ma)
            for (int mb = sb.mode_offset; mb < sb.mode_offset + sb.mode_count; ++mb)
              extra.emplace_back(ma, mb, z(ma) * z(mb));
        }
    }
    SparseMatrix Z(A.rows(), A.cols());
    Z.setFromTriplets(extra.begin(), extra.end());
    A += Z;
  }
  A.makeCompressed();
  if (factor_.factorize(A) != CholmodFactor::Result::Ok)
    throw SolverError(
        "the coarse problem G G' is singular: a group of subdomains is held by no active row "
        "in a way the solver cannot resolve");
}

// Bar model: subdomains linked by active rows form groups; a group containing no
// Dirichlet row can translate along its axis. Its direction z solves g_a z_a + g_b z_b = 0
// for every active row between subdomains a and b (g: the row's column of G).
void CoarseProblem::find_unheld_groups() {
  unheld_.clear();
  if (frame_motions_) {
    unheld_ = frame_motions_->unheld(active_);
    return;
  }
  const Decomposition& d = system_.decomposition();
  if (system_.model().dofs_per_node() != 1) return;  // plane struts are always clamped
  const int count = static_cast<int>(d.subdomains.size());
  std::vector<std::vector<int>> rows_of(count);
  for (int r = 0; r < d.row_count(); ++r)
    if (active_[r])
      for (const RowEntry& entry : d.rows[r].entries)
        rows_of[entry.subdomain].push_back(r);
  const SparseMatrix& G = system_.G();
  auto g = [&](int row, int subdomain) {  // G(mode of subdomain, row)
    return G.coeff(d.subdomains[subdomain].mode_offset, row);
  };
  std::vector<double> value(count, 0.0);
  std::vector<char> seen(count, 0);
  for (int start = 0; start < count; ++start) {
    if (seen[start]) continue;
    UnheldGroup group;
    bool held = false;
    std::queue<int> queue;
    queue.push(start);
    seen[start] = 1;
    value[start] = 1.0;
    while (!queue.empty()) {
      const int a = queue.front();
      queue.pop();
      group.subdomains.push_back(a);
      for (int r : rows_of[a]) {
        const Row& row = d.rows[r];
        if (row.entries.size() < 2) {
          held = true;  // a Dirichlet row
          continue;
        }
        // A row touching two subdomains (the other may be a itself only for degenerate rows).
        const int b =
            row.entries[0].subdomain == a ? row.entries[1].subdomain : row.entries[0].subdomain;
        if (b == a) continue;
        const double gb = g(r, b);
        if (gb == 0.0) continue;
        const double vb = -g(r, a) * value[a] / gb;
        if (!seen[b]) {
          seen[b] = 1;
          value[b] = vb;
          queue.push(b);
        } else if (std::abs(value[b] - vb) > 1e-9 * std::abs(vb)) {
          held = true;  // inconsistent loop: no free translation
        }
      }
    }
    if (held) continue;
    group.direction = Eigen::VectorXd::Zero(d.total_modes);
    for (int s : group.subdomains)
      group.direction(d.subdomains[s].mode_offset) = value[s];
    group.direction.normalize();
    unheld_.push_back(std::move(group));
  }
}

Eigen::VectorXd CoarseProblem::solve(const Eigen::VectorXd& b) const {
  Eigen::VectorXd x(b.size());
  factor_.solve(b.data(), x.data());
  return x;
}

Eigen::VectorXd CoarseProblem::apply_G(const Eigen::VectorXd& v) const {
  return G_hat_ * v;
}

Eigen::VectorXd CoarseProblem::apply_Gt(const Eigen::VectorXd& a) const {
  return G_hat_.transpose() * a;
}

void CoarseProblem::project(Eigen::VectorXd& v) const {
  v -= apply_Gt(solve(apply_G(v)));
}

Eigen::VectorXd CoarseProblem::particular(const Eigen::VectorXd& e) const {
  return apply_Gt(solve(e));
}

Eigen::VectorXd CoarseProblem::amplitudes(const Eigen::VectorXd& r) const {
  return solve(apply_G(r));
}

}  // namespace fetic::solver
