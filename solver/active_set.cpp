#include "solver/active_set.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <utility>

#include <Eigen/LU>

#include "scenes/null_space.hpp"
#include "scenes/union_find.hpp"

namespace fetic::solver {
namespace {

// S = A K^+ A', block by block: each strut contributes only through the rows touching it.
SparseMatrix schur_complement(const PrimalProblem& problem) {
  const RowSparseMatrix& A = problem.contact_rows();
  const SparseMatrix At = A.transpose();  // column k = row k of A
  std::vector<Eigen::Triplet<double>> entries;
  for (const StrutBlock& block : problem.blocks()) {
    std::vector<int> rows;
    for (int k = 0; k < A.rows(); ++k) {
      for (RowSparseMatrix::InnerIterator it(A, k); it; ++it)
        if (it.col() >= block.offset && it.col() < block.offset + block.size) {
          rows.push_back(k);
          break;
        }
    }
    if (rows.empty()) continue;
    const int r = static_cast<int>(rows.size());
    Eigen::MatrixXd local = Eigen::MatrixXd::Zero(block.size, r);  // A_b' restricted
    for (int j = 0; j < r; ++j)
      for (SparseMatrix::InnerIterator it(At, rows[j]); it; ++it)
        if (it.row() >= block.offset && it.row() < block.offset + block.size)
          local(it.row() - block.offset, j) = it.value();
    Eigen::MatrixXd solved(block.size, r);
    block.inverse.apply(local.data(), solved.data(), r);
    const Eigen::MatrixXd Sb = local.transpose() * solved;
    for (int i = 0; i < r; ++i)
      for (int j = 0; j < r; ++j)
        entries.emplace_back(rows[i], rows[j], Sb(i, j));
  }
  SparseMatrix S(A.rows(), A.rows());
  S.setFromTriplets(entries.begin(), entries.end());
  return S;
}

// What rounding alone leaves in a step: g = K x - t f is computed with an error of about
// eps (|K| |x| + |t f| + |A_W' mu|) per entry, and the step is K^+ of it. A beam's
// stiffness spans many orders (bending grows with the inverse cube of the element
// length): on a clamped frame strut of 200 elements the step stalled at 7e-10 of the
// displacements against a tolerance of 1e-10, step after step, until the iteration cap.
// A step no larger than this floor moves nothing the arithmetic can resolve.
double step_rounding_floor(const PrimalProblem& problem, const Eigen::VectorXd& x,
                           const Eigen::VectorXd& load, const Eigen::VectorXd& contact_forces) {
  const SparseMatrix magnitudes = problem.stiffness().cwiseAbs();
  const Eigen::VectorXd bound =
      std::numeric_limits<double>::epsilon() *
      (magnitudes * x.cwiseAbs() + load.cwiseAbs() + contact_forces.cwiseAbs());
  Eigen::VectorXd floor;
  problem.apply_pseudo_inverse(bound, floor);
  return floor.lpNorm<Eigen::Infinity>();
}

}  // namespace

ActiveSet::ActiveSet(const Model& model, const SolveOptions& options)
    : Method(MethodKind::ActiveSet, model, options, 0), problem_(model) {
  if (options.max_iterations <= 0)
    max_iterations_ = 20 * static_cast<int>(model.pairs.size()) + 100;
  S_ = schur_complement(problem_);
  AR_ = SparseMatrix(problem_.contact_rows() * problem_.kernel());
  // The blocks each contact row touches, and the block of each rigid-body mode.
  std::vector<int> block_of(problem_.size(), -1);
  for (int b = 0; b < static_cast<int>(problem_.blocks().size()); ++b) {
    const StrutBlock& block = problem_.blocks()[b];
    for (int i = 0; i < block.size; ++i)
      block_of[block.offset + i] = b;
  }
  const RowSparseMatrix& A = problem_.contact_rows();
  row_blocks_.assign(A.rows(), {});
  for (int k = 0; k < A.rows(); ++k) {
    for (RowSparseMatrix::InnerIterator it(A, k); it; ++it)
      if (std::find(row_blocks_[k].begin(), row_blocks_[k].end(), block_of[it.col()]) ==
          row_blocks_[k].end())
        row_blocks_[k].push_back(block_of[it.col()]);
    if (row_blocks_[k].empty()) row_blocks_[k].push_back(0);  // a row on held DOFs only
  }
  const SparseMatrix& R = problem_.kernel();
  mode_block_.assign(R.cols(), 0);
  for (int m = 0; m < R.cols(); ++m)
    for (SparseMatrix::InnerIterator it(R, m); it; ++it) {
      mode_block_[m] = block_of[it.row()];
      break;
    }
}

double ActiveSet::slack(int row) const {
  return problem_.gaps()(row) - problem_.contact_rows().row(row).dot(x_);
}

void ActiveSet::begin(const Snapshot* warm) {
  const double load_factor = load_factor_;
  const int n = problem_.size();
  x_ = Eigen::VectorXd::Zero(n);
  working_.clear();
  if (warm && warm->primal.size() == n) {
    // The constraints do not depend on the load, so the previous iterate is feasible;
    // its working set is kept where the rows are still active.
    x_ = warm->primal;
    for (int k = 0; k < static_cast<int>(warm->in_working_set.size()); ++k)
      if (warm->in_working_set[k] && std::abs(slack(k)) <= 1e-9 * std::max(1.0, problem_.gaps()(k)))
        working_.push_back(k);
  }
  const Eigen::VectorXd f = load_factor * problem_.load();
  Eigen::VectorXd u0;
  problem_.apply_pseudo_inverse(f, u0);
  const double largest_gap = problem_.gaps().size() ? problem_.gaps().maxCoeff() : 0.0;
  u_scale_ = std::max({u0.lpNorm<Eigen::Infinity>(), largest_gap, x_.lpNorm<Eigen::Infinity>()});
  f_scale_ = f.lpNorm<1>();
  if (!(u_scale_ > 0.0)) u_scale_ = 1.0;
  if (!(f_scale_ > 0.0)) f_scale_ = 1.0;
  g_ = problem_.stiffness() * x_ - f;
  solve_subproblem();
  record_move();
}

// Blocks the working set links: rows of W touching the same strut block, and the block
// modes, form one component; S = A K^+ A' and C = A_W R have no entries between
// components, so the subproblem splits into one small dense system per component (and
// blocks no row of W touches, whose modes are all free). One system over all of W cost
// O(|W|^3) per iteration: 67 s on 2,000 bar pairs, against 7.9 s per component.
std::vector<ActiveSet::Component> ActiveSet::components() const {
  const int blocks = static_cast<int>(problem_.blocks().size());
  scenes::UnionFind sets(blocks);
  const auto root = [&](int b) { return sets.root(b); };
  for (int row : working_)
    for (int b : row_blocks_[row])
      sets.join(b, row_blocks_[row].front());
  std::vector<int> index(blocks, -1);
  std::vector<Component> list;
  auto component_of = [&](int block) -> Component& {
    int& i = index[root(block)];
    if (i < 0) {
      i = static_cast<int>(list.size());
      list.emplace_back();
    }
    return list[i];
  };
  for (int j = 0; j < static_cast<int>(working_.size()); ++j)
    component_of(row_blocks_[working_[j]].front()).rows.push_back(j);
  for (int m = 0; m < static_cast<int>(mode_block_.size()); ++m)
    component_of(mode_block_[m]).modes.push_back(m);
  return list;
}

// Step 1 of a subproblem: per component, the rigid-body modes the working set holds (the
// row space of C = A_W R, rows of W x modes of the component) and those it does not; the
// free ones that the load pushes give the amplitudes of a rigid motion.
ActiveSet::ModeSplit ActiveSet::split_modes(const std::vector<Component>& parts) const {
  const SparseMatrix& R = problem_.kernel();
  const Eigen::VectorXd Rg = R.transpose() * g_;
  ModeSplit split;
  split.held.resize(parts.size());
  split.C.resize(parts.size());
  split.rg.resize(parts.size());
  split.amplitudes = Eigen::VectorXd::Zero(R.cols());
  for (size_t c = 0; c < parts.size(); ++c) {
    const Component& part = parts[c];
    const int cw = static_cast<int>(part.rows.size());
    const int cm = static_cast<int>(part.modes.size());
    split.held[c].resize(cm, 0);
    if (cm == 0) continue;
    Eigen::MatrixXd& C = split.C[c];
    C.resize(cw, cm);
    split.rg[c].resize(cm);
    for (int k = 0; k < cm; ++k) {
      split.rg[c](k) = Rg(part.modes[k]);
      for (int i = 0; i < cw; ++i)
        C(i, k) = AR_.coeff(working_[part.rows[i]], part.modes[k]);
    }
    Eigen::MatrixXd free_basis;
    if (cw == 0) {
      free_basis = Eigen::MatrixXd::Identity(cm, cm);
    } else {
      // The SVD is scenes/null_space.cpp's (Eigen's SVD compiles in one place only).
      scenes::RightSingularSplit modes = scenes::split_right_singular_vectors(C, 1e-10);
      free_basis = std::move(modes.null_space);
      split.held[c] = std::move(modes.row_space);
    }
    if (free_basis.cols() == 0) continue;
    const Eigen::VectorXd h = free_basis.transpose() * split.rg[c];
    if (h.lpNorm<Eigen::Infinity>() > options_.tolerance * f_scale_) split.pushed = true;
    const Eigen::VectorXd a = -(free_basis * h);
    for (int k = 0; k < cm; ++k)
      split.amplitudes(part.modes[k]) = a(k);
  }
  return split;
}

// Unheld and pushed: the move is a rigid motion down the load (zero curvature).
void ActiveSet::take_rigid_motion(const Eigen::VectorXd& amplitudes) {
  p_ = problem_.kernel() * amplitudes;
  moving_struts_.clear();
  for (int j = 0; j < static_cast<int>(amplitudes.size()); ++j)
    if (std::abs(amplitudes(j)) > 1e-12 * amplitudes.lpNorm<Eigen::Infinity>())
      for (int strut : problem_.kernel_struts()[j])
        if (std::find(moving_struts_.begin(), moving_struts_.end(), strut) == moving_struts_.end())
          moving_struts_.push_back(strut);
  multiplier_.assign(working_.size(), 0.0);
  move_ = Move::RigidMotion;
}

// Step 2: per component, the saddle system [S_W -C~; -C~' 0][mu; beta] = [-A_W K^+ g;
// R~'g], C~ = A_W R~ with R~ the held modes. Sets multiplier_; returns R~ beta in mode
// amplitudes.
Eigen::VectorXd ActiveSet::solve_saddle_systems(const std::vector<Component>& parts,
                                                const ModeSplit& split) {
  const RowSparseMatrix& A = problem_.contact_rows();
  Eigen::VectorXd v;
  problem_.apply_pseudo_inverse(g_, v);
  std::vector<int> position(A.rows(), -1);
  multiplier_.assign(working_.size(), 0.0);
  Eigen::VectorXd beta_modes = Eigen::VectorXd::Zero(problem_.kernel().cols());
  for (size_t c = 0; c < parts.size(); ++c) {
    const Component& part = parts[c];
    const int cw = static_cast<int>(part.rows.size());
    const int r = static_cast<int>(split.held[c].cols());
    if (cw + r == 0) continue;
    for (int i = 0; i < cw; ++i)
      position[working_[part.rows[i]]] = i;
    Eigen::MatrixXd M = Eigen::MatrixXd::Zero(cw + r, cw + r);
    Eigen::VectorXd rhs(cw + r);
    for (int j = 0; j < cw; ++j) {
      const int row = working_[part.rows[j]];
      for (SparseMatrix::InnerIterator it(S_, row); it; ++it)
        if (position[it.row()] >= 0) M(position[it.row()], j) = it.value();
      rhs(j) = -A.row(row).dot(v);
    }
    if (r > 0) {
      const Eigen::MatrixXd Ct = split.C[c] * split.held[c];
      M.topRightCorner(cw, r) = -Ct;
      M.bottomLeftCorner(r, cw) = -Ct.transpose();
      rhs.tail(r) = split.held[c].transpose() * split.rg[c];
    }
    const Eigen::VectorXd solution = M.partialPivLu().solve(rhs);
    for (int i = 0; i < cw; ++i) {
      multiplier_[part.rows[i]] = solution(i);
      position[working_[part.rows[i]]] = -1;
    }
    if (r > 0) {
      const Eigen::VectorXd b = split.held[c] * solution.tail(r);
      for (size_t k = 0; k < part.modes.size(); ++k)
        beta_modes(part.modes[k]) = b(static_cast<int>(k));
    }
  }
  return beta_modes;
}

// Step 3: the step p = -K^+(g + A_W' mu) + R~ beta; taken unless it is rounding (checked
// only for steps near the tolerance: one more solve with K), else drop the most negative
// multiplier, or done.
void ActiveSet::choose_move(const Eigen::VectorXd& beta_modes) {
  const RowSparseMatrix& A = problem_.contact_rows();
  const int w = static_cast<int>(working_.size());
  Eigen::VectorXd load_on_free = g_;
  for (int j = 0; j < w; ++j)
    load_on_free += multiplier_[j] * A.row(working_[j]).transpose();
  problem_.apply_pseudo_inverse(load_on_free, p_);
  p_ = -p_;
  if (beta_modes.size() > 0) p_ += problem_.kernel() * beta_modes;

  const double step = p_.lpNorm<Eigen::Infinity>();
  if (step > options_.tolerance * u_scale_ &&
      (step > 1e4 * options_.tolerance * u_scale_ ||
       step >
           step_rounding_floor(problem_, x_, load_factor_ * problem_.load(), load_on_free - g_))) {
    move_ = Move::Step;
    return;
  }
  drop_ = -1;
  double most_negative = -options_.tolerance * f_scale_;
  for (int j = 0; j < w; ++j)
    if (multiplier_[j] < most_negative) {
      most_negative = multiplier_[j];
      drop_ = j;
    }
  move_ = drop_ >= 0 ? Move::Drop : Move::Done;
}

void ActiveSet::solve_subproblem() {
  const std::vector<Component> parts = components();
  const ModeSplit split = split_modes(parts);
  if (split.pushed) {
    take_rigid_motion(split.amplitudes);
    return;
  }
  choose_move(solve_saddle_systems(parts, split));
}

double ActiveSet::ratio_test(double limit) {
  const RowSparseMatrix& A = problem_.contact_rows();
  std::vector<char> in_working(A.rows(), 0);
  for (int k : working_)
    in_working[k] = 1;
  const double p_size = p_.lpNorm<Eigen::Infinity>();
  double step = limit;
  blocking_ = -1;
  for (int k = 0; k < A.rows(); ++k) {
    if (in_working[k]) continue;
    const double ap = A.row(k).dot(p_);
    if (ap <= 1e-12 * p_size) continue;
    const double ratio = std::max(0.0, slack(k)) / ap;
    if (ratio < step) {  // ties keep the lowest row (Bland's rule against cycling)
      step = ratio;
      blocking_ = k;
    }
  }
  return step;
}

void ActiveSet::record_move() {
  double residual = 0.0;
  switch (move_) {
    case Move::Step:
      residual = p_.lpNorm<Eigen::Infinity>() / u_scale_;
      break;
    case Move::RigidMotion:
      residual = (problem_.kernel().transpose() * g_).lpNorm<Eigen::Infinity>() / f_scale_;
      break;
    case Move::Drop:
      residual = -multiplier_[drop_] / f_scale_;
      break;
    case Move::Done:
      residual = p_.lpNorm<Eigen::Infinity>() / u_scale_;
      converge();
      break;
  }
  record(residual, static_cast<int>(working_.size()));
}

void ActiveSet::advance() {
  switch (move_) {
    case Move::Step: {
      const double step = ratio_test(1.0);
      x_ += step * p_;
      if (blocking_ >= 0) working_.push_back(blocking_);
      break;
    }
    case Move::RigidMotion: {
      const double step = ratio_test(std::numeric_limits<double>::infinity());
      if (blocking_ < 0) {
        std::string names;
        for (int s : moving_struts_)
          names += (names.empty() ? "'" : ", '") + model_.strut_names[s] + "'";
        ++iteration_;
        fail("the scene is unbounded at load factor " + std::to_string(load_factor_) +
             ": strut(s) " + names + " held by no support would be pushed away from every contact");
        return;
      }
      x_ += step * p_;
      working_.push_back(blocking_);
      break;
    }
    case Move::Drop:
      working_.erase(working_.begin() + drop_);
      break;
    case Move::Done:
      return;
  }
  g_ = problem_.stiffness() * x_ - load_factor_ * problem_.load();
  ++iteration_;
  solve_subproblem();
  record_move();
}

std::vector<char> ActiveSet::working_set() const {
  std::vector<char> in(model_.pairs.size(), 0);
  for (int row : working_)
    in[row] = 1;
  return in;
}

Snapshot ActiveSet::snapshot() const {
  Snapshot s = snapshot_header();
  const int m = static_cast<int>(model_.pairs.size());
  s.in_working_set.assign(m, 0);
  s.force.assign(m, 0.0);
  for (size_t j = 0; j < working_.size(); ++j) {
    s.in_working_set[working_[j]] = 1;
    if (j < multiplier_.size()) s.force[working_[j]] = std::max(0.0, multiplier_[j]);
  }
  s.pieces = problem_.pieces(x_);
  s.primal = x_;
  return s;
}

}  // namespace fetic::solver
