#include "solver/feti_preconditioner.hpp"

#include <algorithm>
#include <limits>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <utility>

#include "solver/interruption.hpp"
#include "solver/stopwatch.hpp"
#include "solver/threads.hpp"

namespace fetic::solver {
namespace {

// The submatrix K(rows, cols) for sorted index lists given as position maps (-1: absent),
// copied column by column into its exact size: the positions increase with the DOF, so
// K's sorted columns stay sorted (triplets and their sort were 2 s of CPU at 1e7).
SparseMatrix extract(const SparseMatrix& K, const std::vector<int>& row_position, int rows,
                     const std::vector<int>& col_position, int cols) {
  Eigen::Index entries = 0;
  for (int col = 0; col < K.outerSize(); ++col)
    if (col_position[col] >= 0)
      for (SparseMatrix::InnerIterator it(K, col); it; ++it)
        entries += row_position[it.row()] >= 0;
  SparseMatrix S(rows, cols);
  S.reserve(entries);
  for (int col = 0; col < K.outerSize(); ++col) {
    if (col_position[col] < 0) continue;
    S.startVec(col_position[col]);
    for (SparseMatrix::InnerIterator it(K, col); it; ++it)
      if (row_position[it.row()] >= 0)
        S.insertBack(row_position[it.row()], col_position[col]) = it.value();
  }
  S.finalize();
  return S;
}

// K_ib's rows renumbered into the order of K_ii's lean factor `factor` (row k of the
// factor is interior DOF permutation()[k]). Each column keeps its entries in their stored
// order, so that K_ib' v sums them as before: the same bits.
void to_factor_order(SparseMatrix& K_ib, const CompactFactor& factor) {
  K_ib.makeCompressed();
  const std::vector<int> position = factor.positions();
  int* rows = K_ib.innerIndexPtr();
  for (Eigen::Index e = 0; e < K_ib.nonZeros(); ++e)
    rows[e] = position[rows[e]];
}

}  // namespace

// Diagonal stiffness of every DOF the local rows' scaling needs: own subdomains' read
// from their K where needed, the neighbours' asked of their processes (one request and
// one answer). Returns the weights of the own entries of every local row, row after row
// in one list (a map of every DOF and a vector per row were millions of allocations in
// this serial pass at 1e7 unknowns).
std::vector<double> FetiPreconditioner::scaling_weights(bool scaled) const {
  const Decomposition& d = system_.decomposition();
  const DualSpace& space = system_.space();
  const Communicator& comm = space.communicator();
  const auto& ops = system_.subdomains();

  std::map<DofKey, double> remote;  // the neighbours' DOFs' (MPI)
  if (scaled && comm.size() > 1) {
    std::vector<std::set<DofKey>> wanted(comm.size());
    for (int r = 0; r < space.rows(); ++r) {
      const Row& row = d.rows[space.global_row(r)];
      for (const auto* list : {&row.entries, &row.copies})
        for (const RowEntry& entry : *list)
          if (system_.own_index(entry.subdomain) < 0)
            wanted[system_.partition().owner_of(entry.subdomain)].insert(
                {entry.subdomain, entry.dof});
    }
    std::vector<std::vector<double>> requests(comm.size());
    for (int q = 0; q < comm.size(); ++q)
      for (const auto& [sub, dof] : wanted[q]) {
        requests[q].push_back(sub);
        requests[q].push_back(dof);
      }
    const auto asked = comm.all_to_all(requests);
    std::vector<std::vector<double>> answers(comm.size());
    for (int q = 0; q < comm.size(); ++q)
      for (size_t k = 0; k + 1 < asked[q].size(); k += 2) {
        const int sub = static_cast<int>(asked[q][k]), dof = static_cast<int>(asked[q][k + 1]);
        answers[q].push_back(ops[system_.own_index(sub)].K.coeff(dof, dof));
      }
    const auto answered = comm.all_to_all(answers);
    for (int q = 0; q < comm.size(); ++q) {
      size_t k = 0;
      for (const DofKey& key : wanted[q])
        remote[key] = answered[q][k++];
    }
  }
  const auto stiffness = [&](const RowEntry& entry) {
    const int own = system_.own_index(entry.subdomain);
    return own >= 0 ? ops[own].K.coeff(entry.dof, entry.dof)
                    : remote.at({entry.subdomain, entry.dof});
  };

  // An entry of subdomain i in a row shared with subdomain j gets k_j / (sum of k over
  // every copy of the DOF): 1/multiplicity between equal neighbours. Row by row on both
  // cores, each row's weights at its terms (FetiSystem::first_term).
  const int rows = space.rows();
  std::vector<double> weights(static_cast<std::size_t>(system_.first_term(rows)));
#pragma omp parallel num_threads(threads_for(4LL * rows))
  {
    std::vector<std::pair<DofKey, double>> side;  // per row, sorted by key
    std::vector<int> own;                         // the row's own entries, in term order
#pragma omp for schedule(static)
    for (int r = 0; r < rows; ++r) {
      const Row& row = d.rows[space.global_row(r)];
      system_.own_entries_in_order(row, own);
      double* weight = weights.data() + system_.first_term(r);
      row_weights(row, scaled, stiffness, side, own, weight);
    }
  }
  return weights;
}

// One row's weights, at `weight` in the order of `own` (indices into row.entries).
template <class Stiffness>
void FetiPreconditioner::row_weights(const Row& row, bool scaled, const Stiffness& stiffness,
                                     std::vector<std::pair<DofKey, double>>& side,
                                     const std::vector<int>& own, double* weight) {
  // Largest diagonal stiffness per side (a plane contact row has two entries a side).
  // A side is a subdomain; a gluing row's two entries are two sides also when both are
  // in one FETI-DP cluster (corners.hpp).
  const bool gluing = row.kind == RowKind::Gluing;
  auto side_of = [&](const RowEntry& entry) {
    return DofKey{entry.subdomain, gluing ? entry.dof : -1};
  };
  side.clear();
  for (const RowEntry& entry : row.entries) {
    const double k = scaled ? stiffness(entry) : 1.0;
    const DofKey key = side_of(entry);
    auto it = std::lower_bound(side.begin(), side.end(), key,
                               [](const auto& a, const DofKey& b) { return a.first < b; });
    if (it != side.end() && it->first == key)
      it->second = std::max(it->second, k);
    else
      side.insert(it, {key, k});
  }
  double total = 0.0;
  if (scaled && side.size() >= 2) {
    if (row.copies.empty())
      for (const auto& [sub, k] : side)
        total += k;
    else
      for (const RowEntry& copy : row.copies)
        total += stiffness(copy);
  }
  for (int e : own) {
    double w = 1.0;
    if (total > 0.0) {
      double others = 0.0;
      for (const auto& [key, k] : side)
        if (key != side_of(row.entries[e])) others += k;
      w = others / total;
    }
    *weight++ = w;
  }
}

bool FetiPreconditioner::set_up_local(const SubdomainOperator& op, Local& local,
                                      std::vector<int>& b_position) const {
  for (const Incidence& in : op.incidence)
    local.boundary.push_back(in.dof);
  std::sort(local.boundary.begin(), local.boundary.end());
  local.boundary.erase(std::unique(local.boundary.begin(), local.boundary.end()),
                       local.boundary.end());
  const int n = static_cast<int>(op.K.rows());
  const int nb = static_cast<int>(local.boundary.size());
  b_position.assign(n, -1);
  std::vector<int> i_position(n, -1);
  for (int p = 0; p < nb; ++p)
    b_position[local.boundary[p]] = p;
  if (kind_ == Preconditioner::Dirichlet && op.K_plus.has_boundary_schur()) {
    local.schur = &op.K_plus;
    return true;
  }
  int ni = 0;
  for (int dof = 0; dof < n; ++dof)
    if (b_position[dof] < 0) i_position[dof] = ni++;
  // swap, not assign: Eigen's SparseMatrix assignment copies a returned matrix (a copy, its
  // allocation and first touch were most of this function's time).
  SparseMatrix K_bb = extract(op.K, b_position, nb, b_position, nb);
  local.K_bb.swap(K_bb);
  if (kind_ != Preconditioner::Dirichlet || ni == 0) return true;
  SparseMatrix K_ib = extract(op.K, i_position, ni, b_position, nb);
  local.K_ib.swap(K_ib);
  if (op.K_plus.has_interior_solve()) {
    local.interior = &op.K_plus;
    local.interior_factor = op.K_plus.compact_interior_factor();
  } else {
    const SparseMatrix K_ii = extract(op.K, i_position, ni, i_position, ni);
    local.K_ii = std::make_unique<CholmodFactor>();
    if (local.K_ii->factorize(K_ii, true) != CholmodFactor::Result::Ok) return false;
    local.K_ii->compact();  // only solved with from here on
    local.interior_factor = local.K_ii->compact_factor();
  }
  if (!local.interior_factor) return true;
  to_factor_order(local.K_ib, *local.interior_factor);
  const int* rows = local.K_ib.innerIndexPtr();
  const std::vector<int> coupled(rows, rows + local.K_ib.nonZeros());
  // Its own factor is laid out here; K_j's K_ii factor was at factorization, from K's
  // pattern, which covers K_ib's (checked: else the solves take every supernode).
  if (CompactFactor* own = local.K_ii ? local.K_ii->compact_factor() : nullptr)
    own->reach_first(coupled);
  local.reached_only = std::all_of(coupled.begin(), coupled.end(),
                                   [&](int row) { return local.interior_factor->reached(row); });
  return true;
}

FetiPreconditioner::FetiPreconditioner(const FetiSystem& system, Preconditioner kind, bool scaled)
    : system_(system), kind_(kind) {
  Stopwatch watch(setup_seconds_);
  if (kind_ == Preconditioner::None) return;
  const Decomposition& d = system.decomposition();
  const DualSpace& space = system.space();
  const auto& ops = system.subdomains();
  const int count = static_cast<int>(ops.size());
  const std::vector<double> weights = scaling_weights(scaled);  // in the order read below

  local_.resize(count);
  std::vector<std::vector<int>> position_in_boundary(count);
  std::vector<char> interior_failed(count, 0);
  long long work = 0;
  for (const SubdomainOperator& op : ops)
    work += op.K.rows();
    // Every subdomain's blocks and interior factor on its own (both cores: the factors
    // are most of the set-up after K_j's).
#pragma omp parallel for schedule(dynamic) num_threads(threads_for(work * 50))
  for (int i = 0; i < count; ++i) {
    if (stop_requested()) continue;  // Ctrl-C: skip the rest (no throw inside OpenMP)
    interior_failed[i] = !set_up_local(ops[i], local_[i], position_in_boundary[i]);
  }
  throw_if_stopped("setting up the preconditioner");
  int failed = std::numeric_limits<int>::max();  // lowest own subdomain whose interior failed
  int offset = 0;
  for (int i = 0; i < count; ++i) {
    if (interior_failed[i]) {
      // A FETI-DP cluster whose multipliers do not pin its interior (its corners are
      // interior DOFs here): lumped for this cluster. A box of FETI-1 cannot float so.
      if (d.subdomains[ops[i].index].parts.empty())
        failed = std::min(failed, ops[i].index);
      else
        local_[i].K_ii.reset();
    }
    local_[i].offset = offset;
    offset += static_cast<int>(local_[i].boundary.size());
  }
  const std::string error = space.communicator().first_error(
      failed, failed == std::numeric_limits<int>::max()
                  ? std::string()
                  : "Dirichlet preconditioner: the interior of a subdomain of strut '" +
                        system.model().strut_names[d.subdomains[failed].strut] + "' is singular");
  if (!error.empty()) throw SolverError(error);

  // B's scaled entries per own subdomain, and per local row its terms grouped by
  // subdomain in increasing order: the system's terms (FetiSystem::first_term), filled
  // subdomain by subdomain on both cores (a serial pass over the rows before).
  const int rows = space.rows();
  row_first_.resize(static_cast<std::size_t>(rows) + 1);
  for (int r = 0; r <= rows; ++r)
    row_first_[r] = system.first_term(r);
  terms_.resize(static_cast<std::size_t>(row_first_[rows]));
#pragma omp parallel for schedule(dynamic, 16) num_threads(threads_for(row_first_[rows]))
  for (int i = 0; i < count; ++i) {
    const SubdomainOperator& op = ops[i];
    Local& local = local_[i];
    local.incidence.resize(op.incidence.size());
    local.terms = op.terms;
    for (std::size_t k = 0; k < op.incidence.size(); ++k) {
      const Incidence& in = op.incidence[k];
      const int t = op.terms[k];
      const int p = position_in_boundary[i][in.dof];
      const double value = in.value * weights[t];
      local.incidence[k] = {in.row, p, value};
      terms_[t] = {local.offset + p, value, system.term(t).new_subdomain};
    }
  }
  boundary_dofs_ = offset;
  term_values_.resize(terms_.size());
}

void FetiPreconditioner::add_memory(LocalMemory& m) const {
  for (const Local& local : local_) {
    m.preconditioner_factor += static_cast<double>(local.K_ii ? local.K_ii->memory_in_use() : 0);
    m.preconditioner_blocks += sparse_bytes(local.K_bb) + sparse_bytes(local.K_ib);
    m.index += static_cast<double>(local.boundary.capacity()) * sizeof(int);
    m.incidence += static_cast<double>(local.incidence.capacity()) * sizeof(Incidence) +
                   static_cast<double>(local.terms.capacity()) * sizeof(int);
  }
  m.incidence += static_cast<double>(row_first_.capacity()) * sizeof(int) +
                 static_cast<double>(terms_.capacity()) * sizeof(Term);
  m.workspaces += static_cast<double>(term_values_.capacity()) * sizeof(double);
}

double FetiPreconditioner::bytes_read() const {
  double bytes = 0.0;
  for (const Local& local : local_) {
    bytes += 2.0 * sparse_bytes(local.K_ib) + sparse_bytes(local.K_bb);
    if (local.schur)
      bytes += static_cast<double>(local.schur->boundary_schur_bytes());
    else if (local.interior_factor)
      bytes += 2.0 * static_cast<double>(local.reached_only ? local.interior_factor->reached_bytes()
                                                            : local.interior_factor->bytes());
    else if (local.interior)
      bytes += 2.0 * static_cast<double>(local.interior->interior_memory());
    else
      bytes += 2.0 * static_cast<double>(local.K_ii ? local.K_ii->memory_in_use() : 0);
  }
  return bytes;
}

std::size_t FetiPreconditioner::factor_memory() const {
  std::size_t total = 0;
  for (const Local& local : local_)
    total += local.K_ii ? local.K_ii->peak_memory() : 0;
  return total;
}

// y = S_j x for one subdomain (x, y over its boundary DOFs).
void FetiPreconditioner::apply_local(const Local& local, const Eigen::VectorXd& x,
                                     Eigen::VectorXd& y) {
  if (local.schur) {
    local.schur->apply_boundary_schur(x.data(), y.data());
    return;
  }
  y.noalias() = local.K_bb * x;
  if (local.interior_factor) {
    // K_ib's rows in the factor's order: the right-hand side is formed there and
    // solved in place (per thread, not per application: no allocation).
    thread_local Eigen::VectorXd in_factor_order;
    in_factor_order.resize(local.K_ib.rows());
    in_factor_order.noalias() = local.K_ib * x;
    if (local.reached_only)
      local.interior_factor->solve_reached_in_place(in_factor_order.data());
    else
      local.interior_factor->solve_in_place(in_factor_order.data());
    y.noalias() -= local.K_ib.transpose() * in_factor_order;
  } else if (local.interior || (local.K_ii && local.K_ii->size() > 0)) {
    // Per thread, not per application: no allocation in the iterations.
    thread_local Eigen::VectorXd interior_rhs, interior;
    interior_rhs.resize(local.K_ib.rows());
    interior.resize(local.K_ib.rows());
    interior_rhs.noalias() = local.K_ib * x;
    if (local.interior)
      local.interior->interior_solve(interior_rhs.data(), interior.data());
    else
      local.K_ii->solve(interior_rhs.data(), interior.data());
    y.noalias() -= local.K_ib.transpose() * interior;
  }
}

void FetiPreconditioner::apply(const Eigen::VectorXd& w, const std::vector<char>* mask,
                               Eigen::VectorXd& z) const {
  Stopwatch watch(system_.times().preconditioner);
  ++applications_;
  const int rows = static_cast<int>(w.size());
  if (kind_ == Preconditioner::None) {
    z = w;
    if (mask)
      for (int r = 0; r < rows; ++r)
        if (!(*mask)[r]) z(r) = 0.0;
    return;
  }
  const int count = static_cast<int>(local_.size());
#pragma omp parallel for schedule(dynamic, 4) num_threads(threads_for(4LL * boundary_dofs_))
  for (int j = 0; j < count; ++j) {
    const Local& local = local_[j];
    const int nb = static_cast<int>(local.boundary.size());
    thread_local Eigen::VectorXd x, y;  // per thread: no allocation per application
    x.setZero(nb);
    y.resize(nb);
    for (const Incidence& in : local.incidence)
      if (!mask || (*mask)[in.row]) x(in.dof) += in.value * w(in.row);
    apply_local(local, x, y);
    for (std::size_t k = 0; k < local.incidence.size(); ++k)
      term_values_[static_cast<std::size_t>(local.terms[k])] = y(local.incidence[k].dof);
  }
  z.resize(rows);
#pragma omp parallel for schedule(static) num_threads(threads_for(rows))
  for (int r = 0; r < rows; ++r) {
    const int first = row_first_[r];
    z(r) = !mask || (*mask)[r]
               ? sum_row_terms_in_order(terms_.data() + first, terms_.data() + row_first_[r + 1],
                                        term_values_.data() + first)
               : 0.0;
  }
  system_.space().complete_rows(z);
}

}  // namespace fetic::solver
