#include "solver/feti_system.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <string>

#include <omp.h>

#include "solver/corners.hpp"
#include "solver/interruption.hpp"
#include "solver/primal_problem.hpp"
#include "solver/rigid_modes.hpp"
#include "solver/stopwatch.hpp"
#include "solver/threads.hpp"

namespace fetic::solver {
namespace {

constexpr double kSingularRcond = 1e-15;

// Sorts [first, last) by `less`, stably, by insertion: for the few items of a row of B
// or a column of G (std::stable_sort allocated per call).
template <class Iterator, class Less>
void insertion_sort(Iterator first, Iterator last, Less less) {
  for (Iterator k = first; k != last; ++k)
    for (Iterator j = k; j != first && less(*j, *(j - 1)); --j)
      std::iter_swap(j - 1, j);
}

Decomposition decomposition_for(const Model& model, int corner_clusters, bool edge_averages) {
  Decomposition boxes = decompose(model);
  if (corner_clusters == 0) return boxes;
  return join_corners(model, boxes, std::max(corner_clusters, 0), edge_averages);
}

// K's columns in `boundary` (sorted), the others emptied; same order as K. `diagonal_only`:
// only their diagonal entries.
SparseMatrix boundary_columns(const SparseMatrix& K, const std::vector<int>& boundary,
                              bool diagonal_only) {
  SparseMatrix kept(K.rows(), K.cols());
  long long entries = 0;
  for (int col : boundary)
    entries += diagonal_only ? 1 : K.outerIndexPtr()[col + 1] - K.outerIndexPtr()[col];
  kept.reserve(static_cast<Eigen::Index>(entries));
  size_t next = 0;
  for (int col = 0; col < K.outerSize(); ++col) {
    kept.startVec(col);
    if (next < boundary.size() && boundary[next] == col) {
      ++next;
      for (SparseMatrix::InnerIterator it(K, col); it; ++it)
        if (!diagonal_only || it.row() == col) kept.insertBack(it.row(), col) = it.value();
    }
  }
  kept.finalize();
  return kept;
}

}  // namespace

namespace {

// Times the construction of a member in the initializer list.
template <class Build>
auto timed(double& seconds, Build build) {
  Stopwatch watch(seconds);
  return build();
}

}  // namespace

FetiSystem::FetiSystem(const Model& model, const Communicator& communicator, bool interior_first,
                       int corner_clusters, bool single_factors, bool single_interior,
                       bool edge_averages, bool boundary_last)
    : model_(model),
      decomposition_(
          timed(setup_times_.decomposition,
                [&] { return decomposition_for(model, corner_clusters, edge_averages); })),
      partition_(partition_subdomains(decomposition_, communicator.size())),
      space_(decomposition_, partition_, communicator) {
  build_incidence();
  {
    Stopwatch watch(setup_times_.factorization);
    factorize_subdomains({interior_first, single_factors, single_interior, boundary_last});
  }
  Stopwatch watch(setup_times_.coarse_space);
  c_ = Eigen::VectorXd::Zero(space_.rows());
  for (int r = 0; r < space_.rows(); ++r)
    c_(r) = decomposition_.rows[space_.global_row(r)].rhs;
  build_G();
  build_redundant_groups();
}

void FetiSystem::own_entries_in_order(const Row& row, std::vector<int>& out) const {
  out.clear();
  for (int e = 0; e < static_cast<int>(row.entries.size()); ++e)
    if (own_index_[row.entries[e].subdomain] >= 0) out.push_back(e);
  insertion_sort(out.begin(), out.end(), [&row](int a, int b) {
    return row.entries[a].subdomain < row.entries[b].subdomain;
  });
}

void FetiSystem::build_incidence() {
  Stopwatch watch(setup_times_.incidence);
  const Decomposition& d = decomposition_;
  const Communicator& communicator = space_.communicator();
  const std::vector<int>& own = partition_.owned[communicator.rank()];
  own_index_.assign(d.subdomains.size(), -1);
  subdomains_.resize(own.size());
  dof_offsets_.resize(own.size());
  int dofs = 0;
  for (size_t i = 0; i < own.size(); ++i) {
    own_index_[own[i]] = static_cast<int>(i);
    subdomains_[i].index = own[i];
    dof_offsets_[i] = dofs;
    dofs += d.subdomains[own[i]].dof_count;
  }
  fill_terms_and_incidence();
  x_.resize(dofs);
  y_.resize(dofs);
  boundary_y_.resize(part_entries_.size());
}

// B's entries per own subdomain, and per local row the own entries grouped by subdomain,
// on both cores: each thread takes a block of rows, orders each row's own entries once
// (kept, row after row) and counts its rows' terms and its entries per subdomain, then
// writes them where the counts before it end - the order a serial pass row after row
// gives (which was 0.75 s of CPU at 1e7).
void FetiSystem::fill_terms_and_incidence() {
  const Decomposition& d = decomposition_;
  const int rows = space_.rows();
  const int count = static_cast<int>(subdomains_.size());
  row_parts_.resize(static_cast<std::size_t>(rows));
  const int threads = threads_for(4LL * rows);
  // Per thread, per own subdomain: its entries in the thread's rows, then the entries
  // of the threads before it.
  std::vector<std::vector<int>> before(static_cast<std::size_t>(threads));
#pragma omp parallel num_threads(threads)
  {
    const int team = omp_get_num_threads(), t = omp_get_thread_num();
    const int begin = static_cast<int>(1LL * rows * t / team);
    const int end = static_cast<int>(1LL * rows * (t + 1) / team);
    std::vector<int>& mine = before[t];
    mine.assign(static_cast<std::size_t>(count), 0);
    std::vector<int> order, orders;  // orders: each row's order, row after row
    for (int r = begin; r < end; ++r) {
      const Row& row = d.rows[space_.global_row(r)];
      own_entries_in_order(row, order);
      row_parts_[r].end = static_cast<int>(order.size());
      for (int e : order)
        ++mine[own_index_[row.entries[e].subdomain]];
      orders.insert(orders.end(), order.begin(), order.end());
    }
#pragma omp barrier
#pragma omp single nowait
    {
      int at = 0;
      for (RowPart& part : row_parts_) {
        part.first = at;
        at += part.end;
        part.end = at;
      }
      part_entries_.resize(static_cast<std::size_t>(at));
    }
#pragma omp for schedule(static)
    for (int i = 0; i < count; ++i) {
      int total = 0;
      for (int q = 0; q < team; ++q) {
        const int n = before[q][i];
        before[q][i] = total;
        total += n;
      }
      subdomains_[i].incidence.resize(static_cast<std::size_t>(total));
      subdomains_[i].terms.resize(static_cast<std::size_t>(total));
    }
    const int* next = orders.data();
    for (int r = begin; r < end; ++r)
      write_row_terms(r, next, mine);
  }
}

// Row r's terms and its entries of the own subdomains' incidence, its own entries taken
// in order from `next` on; `at`: per own subdomain, where its next entry goes.
void FetiSystem::write_row_terms(int r, const int*& next, std::vector<int>& at) {
  const Row& row = decomposition_.rows[space_.global_row(r)];
  int previous = -1;
  for (int term = row_parts_[r].first; term < row_parts_[r].end; ++term) {
    const RowEntry& entry = row.entries[*next++];
    const int i = own_index_[entry.subdomain];
    part_entries_[term] = {dof_offsets_[i] + entry.dof, entry.value,
                           previous >= 0 && entry.subdomain != previous};
    previous = entry.subdomain;
    SubdomainOperator& op = subdomains_[i];
    const int k = at[i]++;
    op.incidence[k] = {r, entry.dof, entry.value};
    op.terms[k] = term;
  }
}

namespace {

// Per entry of B_j, its DOF's row in K_j^+'s lean factor (-1: a fixed DOF); empty when
// there is no lean factor.
std::vector<int> factor_positions(const GeneralizedInverse& K_plus,
                                  const std::vector<Incidence>& incidence) {
  const CompactFactor* factor = K_plus.compact_factor();
  if (!factor) return {};
  std::vector<int> position(static_cast<std::size_t>(K_plus.size()), -1);
  const std::vector<int>& kept = K_plus.kept_dofs();
  const std::vector<int> in_factor = factor->positions();
  for (std::size_t j = 0; j < in_factor.size(); ++j)
    position[kept[j]] = in_factor[j];
  std::vector<int> positions;
  positions.reserve(incidence.size());
  for (const Incidence& in : incidence)
    positions.push_back(position[in.dof]);
  return positions;
}

}  // namespace

void FetiSystem::factorize_subdomains(const FactorOptions& options) {
  const Decomposition& d = decomposition_;
  const int count = static_cast<int>(subdomains_.size());
  std::vector<CholmodFactor::Result> results(count, CholmodFactor::Result::Ok);
  std::vector<char> singular(count, 0);
  long long work = 0;
  for (const SubdomainOperator& op : subdomains_)
    work += d.subdomains[op.index].dof_count;
#pragma omp parallel for schedule(dynamic) num_threads(threads_for(work * 50))
  for (int i = 0; i < count; ++i) {
    if (stop_requested()) continue;  // Ctrl-C: skip the rest (no throw inside OpenMP)
    SubdomainOperator& op = subdomains_[i];
    const Subdomain& sub = d.subdomains[op.index];
    // swap, not assign: Eigen's SparseMatrix assignment copies into the target's storage
    // and keeps its capacity, so an assigned-over K_j kept every byte it ever had.
    SparseMatrix K = subdomain_stiffness(model_, sub);
    op.K.swap(K);
    op.R = subdomain_modes(model_, sub);
    op.K_plus.use_single_precision(options.single_factors);
    op.K_plus.use_single_precision_interior(options.single_interior);
    op.K_plus.use_simplicial_when_small(true);
    op.K_plus.use_boundary_last(options.boundary_last);
    // Not for FETI-DP's clusters: their boundary (every torn interface DOF of the
    // cluster's boxes, coupled through the corners) would be one dense trailing block.
    if (options.interior_first && sub.parts.empty()) {
      std::vector<int> boundary;  // as the preconditioner finds it: the DOFs B touches
      for (const Incidence& in : op.incidence)
        boundary.push_back(in.dof);
      std::sort(boundary.begin(), boundary.end());
      boundary.erase(std::unique(boundary.begin(), boundary.end()), boundary.end());
      results[i] = op.K_plus.factorize(op.K, op.R, boundary);
      // The preconditioner reads only K_j's boundary columns (K_bb, K_ib and the
      // diagonal at B's DOFs) when K_j's factor solves with K_ii: the rest goes now, not
      // after every subdomain is factorized (K_j is about a quarter of the factor).
      if (op.K_plus.has_interior_solve() || op.K_plus.has_boundary_schur()) {
        // From the factor's trailing block S_j needs no K_bb: the diagonal at B's DOFs
        // (the preconditioner's scaling) is all that is read of K_j.
        SparseMatrix cut = boundary_columns(op.K, boundary, op.K_plus.has_boundary_schur());
        op.K.swap(cut);
      }
    } else {
      results[i] = op.K_plus.factorize(op.K, op.R);
    }
    singular[i] = results[i] == CholmodFactor::Result::Ok && op.K_plus.rcond() < kSingularRcond;
    if (results[i] == CholmodFactor::Result::Ok)
      op.positions = factor_positions(op.K_plus, op.incidence);
    if (!op.positions.empty()) {
      // The fused pass solves on B_j's DOFs alone (the fixed ones, -1, not in the factor).
      std::vector<int> rows;
      for (int p : op.positions)
        if (p >= 0) rows.push_back(p);
      op.K_plus.reach_first(rows);
    }
  }
  throw_if_stopped("factorizing the subdomains");
  // The lowest failing subdomain of any process is reported, by every process alike.
  int failed = std::numeric_limits<int>::max();
  std::string message;
  for (int i = 0; i < count; ++i)
    if (results[i] != CholmodFactor::Result::Ok || singular[i]) {
      const Subdomain& sub = d.subdomains[subdomains_[i].index];
      failed = subdomains_[i].index;
      message = singular_message(model_, sub.strut, results[i],
                                 "its subdomain at nodes " + std::to_string(sub.box.i0) + ".." +
                                     std::to_string(sub.box.i1));
      break;
    }
  message = communicator().first_error(failed, message);
  if (!message.empty()) throw SolverError(message);
}

namespace {

// Column r of G, B's row r times the rigid motions of the subdomains it touches: per entry
// of the row, R's nonzeros at its DOF times its value, as (mode, value) sorted by mode and
// each mode once, its terms summed in the row's order - as setFromTriplets() sums them.
void column_of_G(const Row& row, const Decomposition& d,
                 const std::function<const Eigen::MatrixXd&(int)>& modes_of,
                 std::vector<std::pair<int, double>>& column) {
  column.clear();
  for (const RowEntry& entry : row.entries) {
    const Subdomain& sub = d.subdomains[entry.subdomain];
    const Eigen::MatrixXd& R = modes_of(entry.subdomain);
    for (int m = 0; m < sub.mode_count; ++m)
      if (R(entry.dof, m) != 0.0)
        column.emplace_back(sub.mode_offset + m, R(entry.dof, m) * entry.value);
  }
  insertion_sort(column.begin(), column.end(),
                 [](const auto& a, const auto& b) { return a.first < b.first; });
  std::size_t kept = 0;
  for (std::size_t k = 0; k < column.size(); ++k) {
    if (kept > 0 && column[kept - 1].first == column[k].first)
      column[kept - 1].second = column[kept - 1].second + column[k].second;
    else
      column[kept++] = column[k];
  }
  column.resize(kept);
}

}  // namespace

// G and |G| column by column on both cores: counted, then written straight into their
// compressed arrays (the triplets and their sort were a serial pass over every row).
void FetiSystem::build_G() {
  const Decomposition& d = decomposition_;
  std::map<int, Eigen::MatrixXd> remote_modes;  // rigid motions of neighbours' subdomains
  if (communicator().distributed())
    for (int r = 0; r < space_.rows(); ++r)
      for (const RowEntry& entry : d.rows[space_.global_row(r)].entries)
        if (own_index_[entry.subdomain] < 0 && !remote_modes.count(entry.subdomain))
          remote_modes.emplace(entry.subdomain,
                               subdomain_modes(model_, d.subdomains[entry.subdomain]));
  const std::function<const Eigen::MatrixXd&(int)> modes_of =
      [&](int subdomain) -> const Eigen::MatrixXd& {
    const int i = own_index_[subdomain];
    return i >= 0 ? subdomains_[i].R : remote_modes.at(subdomain);
  };
  const int rows = space_.rows();
  G_.resize(d.total_modes, rows);
  int* first = G_.outerIndexPtr();
  const int threads = threads_for(8LL * rows);
#pragma omp parallel num_threads(threads)
  {
    std::vector<std::pair<int, double>> column;
#pragma omp for schedule(static)
    for (int r = 0; r < rows; ++r) {
      column_of_G(d.rows[space_.global_row(r)], d, modes_of, column);
      first[r + 1] = static_cast<int>(column.size());
    }
#pragma omp single
    {
      for (int r = 0; r < rows; ++r)
        first[r + 1] += first[r];
      G_.resizeNonZeros(first[rows]);
      G_abs_.resize(d.total_modes, rows);  // the same pattern, its values' magnitudes
      G_abs_.resizeNonZeros(first[rows]);
      std::copy(first, first + rows + 1, G_abs_.outerIndexPtr());
    }
#pragma omp for schedule(static)
    for (int r = 0; r < rows; ++r) {
      column_of_G(d.rows[space_.global_row(r)], d, modes_of, column);
      for (std::size_t k = 0; k < column.size(); ++k) {
        const int at = first[r] + static_cast<int>(k);
        G_.innerIndexPtr()[at] = G_abs_.innerIndexPtr()[at] = column[k].first;
        G_.valuePtr()[at] = column[k].second;
        G_abs_.valuePtr()[at] = std::abs(column[k].second);
      }
    }
  }
}

void FetiSystem::build_redundant_groups() {
  for (const RedundantGroup& group : decomposition_.redundant_groups) {
    LocalGroup local;
    local.copies = group.copies;
    local.own_end.assign(group.copies, 0);
    bool held = false;
    for (size_t k = 0; k < group.rows.size(); ++k) {
      const Row& row = decomposition_.rows[group.rows[k]];
      const auto [i, j] = group.ends[k];
      // entries[0] is copy i, entries[1] copy j (decompose()).
      local.own_end[i] = own_index_[row.entries[0].subdomain] >= 0;
      local.own_end[j] = own_index_[row.entries[1].subdomain] >= 0;
      const int r = space_.local_row(group.rows[k]);
      held = held || r >= 0;
      local.rows.push_back(r);
      local.ends.push_back(group.ends[k]);
    }
    if (held) groups_.push_back(std::move(local));
  }
  std::vector<char> in_group(static_cast<std::size_t>(space_.rows()), 0);
  for (const LocalGroup& group : groups_)
    for (int r : group.rows)
      if (r >= 0) {
        groups_disjoint_ = groups_disjoint_ && !in_group[static_cast<std::size_t>(r)];
        in_group[static_cast<std::size_t>(r)] = 1;
      }
}

void FetiSystem::solve_subdomains(const Eigen::VectorXd* lambda, double s, double load_factor,
                                  bool whole) const {
  Stopwatch watch(times_.local_solves);
  ++subdomain_passes_;
  const Decomposition& d = decomposition_;
  const int count = static_cast<int>(subdomains_.size());
#pragma omp parallel for schedule(dynamic, 4) num_threads(threads_for(x_.size()))
  for (int i = 0; i < count; ++i) {
    const SubdomainOperator& op = subdomains_[i];
    if (!whole && load_factor == 0.0 && !op.positions.empty()) {
      solve_subdomain_fused(i, lambda, s);
      continue;
    }
    const Subdomain& sub = d.subdomains[op.index];
    auto x = x_.segment(dof_offsets_[i], sub.dof_count);
    auto y = y_.segment(dof_offsets_[i], sub.dof_count);
    if (load_factor != 0.0)
      x = load_factor * sub.load;
    else
      x.setZero();
    if (lambda)
      for (const Incidence& in : op.incidence)
        x(in.dof) += s * in.value * (*lambda)(in.row);
    // K^+ 0 = 0: a subdomain the vector does not touch needs no solve (FETI-DP's contact
    // coarse space applies F to columns that touch two clusters).
    if (x.isZero(0.0))
      y.setZero();
    else
      op.K_plus.apply(x.data(), y.data());
    for (std::size_t k = 0; k < op.incidence.size(); ++k)
      boundary_y_[static_cast<std::size_t>(op.terms[k])] = y(op.incidence[k].dof);
  }
}

// The same numbers as the general path in solve_subdomains, in the same order: each
// entry of the factor's vector sums its terms of B_j' lambda from zero, the solve is
// CompactFactor's, and a fixed DOF's value is zero.
void FetiSystem::solve_subdomain_fused(int i, const Eigen::VectorXd* lambda, double s) const {
  const SubdomainOperator& op = subdomains_[i];
  const std::size_t entries = op.incidence.size();
  // Per thread, not per subdomain: no allocation in the iterations.
  thread_local std::vector<double> work;
  work.resize(static_cast<std::size_t>(op.K_plus.compact_factor()->size()));
  std::fill(work.begin(), work.end(), 0.0);
  bool touched = false;
  if (lambda)
    for (std::size_t k = 0; k < entries; ++k) {
      const Incidence& in = op.incidence[k];
      const double term = s * in.value * (*lambda)(in.row);
      touched = touched || term != 0.0;
      if (op.positions[k] >= 0) work[static_cast<std::size_t>(op.positions[k])] += term;
    }
  if (touched) {
    // One factor with the boundary last: B's rows are its trailing rows, and their solve
    // needs its trailing columns alone (solver/boundary_last.hpp).
    if (op.K_plus.has_boundary_schur())
      op.K_plus.compact_factor()->solve_trailing_in_place(op.K_plus.boundary_schur_first(),
                                                          work.data());
    else
      op.K_plus.compact_factor()->solve_reached_in_place(work.data());
  }
  for (std::size_t k = 0; k < entries; ++k)
    boundary_y_[static_cast<std::size_t>(op.terms[k])] =
        op.positions[k] >= 0 ? work[static_cast<std::size_t>(op.positions[k])] : 0.0;
}

void FetiSystem::gather_rows(Eigen::VectorXd& out) const {
  const int rows = space_.rows();
  out.resize(rows);
  {
    Stopwatch watch(times_.local_solves);
#pragma omp parallel for schedule(static) num_threads(threads_for(rows))
    for (int r = 0; r < rows; ++r) {
      const int first = row_parts_[r].first;
      out(r) = sum_row_terms_in_order(part_entries_.data() + first,
                                      part_entries_.data() + row_parts_[r].end,
                                      boundary_y_.data() + first);
    }
  }
  space_.complete_rows(out);
}

void FetiSystem::apply_B(const Eigen::VectorXd& u, Eigen::VectorXd& out) const {
  sum_rows(u, out);
}

void FetiSystem::sum_rows(const Eigen::VectorXd& values, Eigen::VectorXd& out) const {
  const int rows = space_.rows();
  out.resize(rows);
  {
    Stopwatch watch(times_.local_solves);
#pragma omp parallel for schedule(static) num_threads(threads_for(rows))
    for (int r = 0; r < rows; ++r) {
      const PartEntry* entries = part_entries_.data();
      out(r) = sum_row_terms(entries + row_parts_[r].first, entries + row_parts_[r].end, values);
    }
  }
  space_.complete_rows(out);
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
  ++f_applications_;
  solve_subdomains(nullptr, 0.0, load_factor);
  Eigen::VectorXd out;
  gather_rows(out);
  return out - c_;
}

Eigen::VectorXd FetiSystem::assemble_modes(const std::vector<double>& own) const {
  const Communicator& comm = communicator();
  const Decomposition& d = decomposition_;
  Eigen::VectorXd modes = Eigen::VectorXd::Zero(d.total_modes);
  const std::vector<double> all = comm.all_gather(own);
  size_t at = 0;
  for (int q = 0; q < comm.size(); ++q)
    for (int s : partition_.owned[q]) {
      const Subdomain& sub = d.subdomains[s];
      for (int m = 0; m < sub.mode_count; ++m)
        modes(sub.mode_offset + m) = all[at++];
    }
  return modes;
}

Eigen::VectorXd FetiSystem::e(double load_factor) const {
  std::vector<double> own;
  for (const SubdomainOperator& op : subdomains_) {
    const Eigen::VectorXd block =
        load_factor * (op.R.transpose() * decomposition_.subdomains[op.index].load);
    own.insert(own.end(), block.data(), block.data() + block.size());
  }
  return assemble_modes(own);
}

Eigen::VectorXd FetiSystem::apply_G(const Eigen::VectorXd& v, const std::vector<char>* mask) const {
  return own_modes_product(G_, v, mask);
}

void FetiSystem::subtract_Gt(const Eigen::VectorXd& a, Eigen::VectorXd& v,
                             const std::vector<char>* mask) const {
  Stopwatch watch(times_.mode_products);
  const int rows = static_cast<int>(G_.outerSize());
#pragma omp parallel for schedule(static) num_threads(threads_for(G_.nonZeros()))
  for (int r = 0; r < rows; ++r) {
    if (mask && !(*mask)[r]) continue;
    double sum = 0.0;  // as Eigen's sparse' * dense product sums a row
    for (SparseMatrix::InnerIterator it(G_, r); it; ++it)
      sum += it.value() * a(it.row());
    v(r) -= sum;
  }
}

Eigen::VectorXd FetiSystem::apply_abs_G(const Eigen::VectorXd& v) const {
  return own_modes_product(G_abs_, v.cwiseAbs(), nullptr);
}

Eigen::VectorXd FetiSystem::own_modes_product(const SparseMatrix& M, const Eigen::VectorXd& v,
                                              const std::vector<char>* mask) const {
  // The own subdomains' modes of M v; each sums its rows in increasing global order, the
  // same for any number of processes (a neighbour's modes are left to its process).
  Stopwatch watch(times_.mode_products);
  Eigen::VectorXd local = Eigen::VectorXd::Zero(decomposition_.total_modes);
  for (int r = 0; r < M.outerSize(); ++r) {
    if (mask && !(*mask)[r]) continue;
    for (SparseMatrix::InnerIterator it(M, r); it; ++it)
      local(it.row()) += it.value() * v(r);
  }
  if (!communicator().distributed()) return local;
  std::vector<double> own;
  for (const SubdomainOperator& op : subdomains_) {
    const Subdomain& sub = decomposition_.subdomains[op.index];
    own.insert(own.end(), local.data() + sub.mode_offset,
               local.data() + sub.mode_offset + sub.mode_count);
  }
  return assemble_modes(own);
}

Eigen::VectorXd FetiSystem::subdomain_displacements(const Eigen::VectorXd& lambda,
                                                    const Eigen::VectorXd& alpha,
                                                    double load_factor) const {
  solve_subdomains(&lambda, -1.0, load_factor, true);
  // y_ is only written before it is read: take its pages instead of copying them into
  // fresh ones (at 1e7 unknowns 77 MB, 19,000 first touches of 10-30 us on this VM) and
  // leave it a new, untouched room for the next solve.
  Eigen::VectorXd u = std::move(y_);
  y_.resize(u.size());
  for (size_t i = 0; i < subdomains_.size(); ++i) {
    const Subdomain& sub = decomposition_.subdomains[subdomains_[i].index];
    u.segment(dof_offsets_[i], sub.dof_count) +=
        subdomains_[i].R * alpha.segment(sub.mode_offset, sub.mode_count);
    for (const Subdomain::TiedDof& tie : sub.ties) {  // edge averages (edge_averages.hpp)
      double value = 0.0;
      for (const auto& [dof, coefficient] : tie.terms)
        value += coefficient * u(dof_offsets_[i] + dof);
      u(dof_offsets_[i] + tie.dof) = value;
    }
  }
  return u;
}

std::vector<Piece> FetiSystem::pieces(const Eigen::VectorXd& lambda, const Eigen::VectorXd& alpha,
                                      double load_factor) const {
  const Eigen::VectorXd u = subdomain_displacements(lambda, alpha, load_factor);
  std::vector<std::pair<int, Piece>> numbered;  // (piece index, piece)
  for (size_t i = 0; i < subdomains_.size(); ++i) {
    const Subdomain& sub = decomposition_.subdomains[subdomains_[i].index];
    for (const SubdomainPart& part : parts_of(sub, subdomains_[i].index)) {
      const StrutMesh& mesh = model_.struts[part.strut];
      Piece piece;
      piece.strut = part.strut;
      piece.box = part.box;
      piece.displacement.reserve(part.box.node_count());
      double node[3];
      for (int n = 0; n < part.box.node_count(); ++n) {
        for (int c = 0; c < mesh.dofs_per_node; ++c) {
          const int local = n * mesh.dofs_per_node + c;
          node[c] = u(dof_offsets_[i] + (part.dofs.empty() ? local : part.dofs[local]));
        }
        add_node_state(mesh, node, piece);
      }
      numbered.emplace_back(part.piece, std::move(piece));
    }
  }
  // In the order of the boxes (clusters may interleave them).
  std::stable_sort(numbered.begin(), numbered.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<Piece> result;
  result.reserve(numbered.size());
  for (auto& item : numbered)
    result.push_back(std::move(item.second));
  return result;
}

void FetiSystem::project_onto_range_of_B(Eigen::VectorXd& v) const {
  // Every process takes part when any has redundant rows (the exchange below is collective
  // among neighbours), also one that holds none of them.
  if (decomposition_.redundant_groups.empty()) return;
  Stopwatch watch(times_.range_projection);
  // Each row's new value (s_i - s_j) / m, s_c = B_g' v for copy c, is the sum of one part
  // per end: s_i / m from the process of copy i, -s_j / m from that of copy j. Rows of no
  // group keep their value (on the owning process; the others add zero).
  // In one process v is projected in place: no copy of it and back (a group reads its
  // rows before it writes them, and no row is in two groups).
  const bool distributed = communicator().distributed();
  if (!distributed && groups_disjoint_) {
    project_groups(v, v);
    return;
  }
  Eigen::VectorXd partial = v;
  if (distributed)
    for (int r = 0; r < space_.rows(); ++r)
      if (!space_.owned(r)) partial(r) = 0.0;
  project_groups(v, partial);
  if (distributed) space_.complete_rows(partial);
  v = partial;
}

// partial(r) = the projection's part of this process for each row r of a group, from v
// (the groups on both threads: each writes only its own rows).
void FetiSystem::project_groups(const Eigen::VectorXd& v, Eigen::VectorXd& partial) const {
  const int count = static_cast<int>(groups_.size());
#pragma omp parallel for schedule(static) num_threads(threads_for(8LL * count))
  for (int g = 0; g < count; ++g) {
    const LocalGroup& group = groups_[g];
    double copy_sum[64];  // per copy (a node has at most four copies)
    const int m = std::min(group.copies, 64);
    std::fill(copy_sum, copy_sum + m, 0.0);
    for (size_t k = 0; k < group.rows.size(); ++k) {
      const int r = group.rows[k];
      if (r < 0) continue;
      const auto [i, j] = group.ends[k];
      if (group.own_end[i]) copy_sum[i] += v(r);
      if (group.own_end[j]) copy_sum[j] -= v(r);
    }
    for (size_t k = 0; k < group.rows.size(); ++k) {
      const int r = group.rows[k];
      if (r < 0) continue;
      const auto [i, j] = group.ends[k];
      const double from_i = group.own_end[i] ? copy_sum[i] / m : 0.0;
      const double from_j = group.own_end[j] ? -copy_sum[j] / m : 0.0;
      partial(r) = group.own_end[i] && group.own_end[j] ? from_i + from_j
                                                        : (group.own_end[i] ? from_i : from_j);
    }
  }
}

void FetiSystem::release_stiffness() {
  for (SubdomainOperator& op : subdomains_) {
    SparseMatrix empty;  // swapped in: assigning an empty matrix would keep K_j's storage
    op.K.swap(empty);
  }
}

double FetiSystem::f_bytes_read() const {
  double bytes = 0.0;
  for (const SubdomainOperator& op : subdomains_) {
    const CompactFactor* factor = op.K_plus.compact_factor();
    if (factor && !op.positions.empty() && op.K_plus.has_boundary_schur())
      bytes += 2.0 * static_cast<double>(factor->trailing_bytes(op.K_plus.boundary_schur_first()));
    else
      bytes +=
          2.0 * static_cast<double>(factor && !op.positions.empty() ? factor->reached_bytes()
                                                                    : op.K_plus.factor_memory());
  }
  return bytes;
}

LocalMemory FetiSystem::memory() const {
  LocalMemory m;
  for (const SubdomainOperator& op : subdomains_) {
    m.stiffness += sparse_bytes(op.K);
    m.factor += static_cast<double>(op.K_plus.factor_memory());
    m.preconditioner_factor += static_cast<double>(op.K_plus.interior_memory());
    m.index += static_cast<double>(op.K_plus.index_memory());
    m.rigid_modes += static_cast<double>(op.R.size()) * sizeof(double);
    m.incidence += static_cast<double>(op.incidence.capacity()) * sizeof(Incidence) +
                   static_cast<double>(op.positions.capacity() + op.terms.capacity()) * sizeof(int);
  }
  for (const SubdomainOperator& op : subdomains_)
    m.loads +=
        static_cast<double>(decomposition_.subdomains[op.index].load.size()) * sizeof(double);
  m.incidence += static_cast<double>(row_parts_.capacity()) * sizeof(RowPart) +
                 static_cast<double>(part_entries_.capacity()) * sizeof(PartEntry);
  m.rigid_modes += sparse_bytes(G_) + sparse_bytes(G_abs_);
  m.index += static_cast<double>(own_index_.capacity() + dof_offsets_.capacity()) * sizeof(int);
  m.workspaces +=
      static_cast<double>(x_.size() + y_.size() + boundary_y_.capacity()) * sizeof(double);
  return m;
}

std::size_t FetiSystem::factor_memory() const {
  std::size_t total = 0;
  for (const SubdomainOperator& op : subdomains_)
    total += op.K_plus.peak_memory();
  return total;
}

}  // namespace fetic::solver
