#include "solver/feti_method.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include "solver/stopwatch.hpp"

namespace fetic::solver {

FetiMethod::FetiMethod(MethodKind kind, const Model& model, const SolveOptions& options,
                       int default_max_iterations, const Communicator& communicator)
    : Method(kind, model, options, default_max_iterations),
      system_(model, communicator,
              options.preconditioner == Preconditioner::Dirichlet && options.shared_interior_factor,
              options.corner_clusters, options.single_factors, options.single_interior_factors,
              options.edge_averages, options.boundary_last_factor),
      preconditioner_(system_, options.preconditioner, options.scaling),
      coarse_([this] {
        Stopwatch watch(coarse_setup_seconds_);
        return CoarseProblem(system_);
      }()) {
  system_.release_stiffness();
}

namespace {

// (G'z)_k on the rows that the modes of `direction` reach, as (row, rate) in increasing row
// order; `along` is zero on entry and on return. Accumulated mode by mode in increasing
// mode order, as the dense product G' z adds them.
void reached_rows(const SparseMatrix& Gt, const Eigen::SparseVector<double>& direction,
                  std::vector<double>& along, std::vector<std::pair<int, double>>& out) {
  std::vector<int> reached;
  for (Eigen::SparseVector<double>::InnerIterator mode(direction); mode; ++mode)
    for (SparseMatrix::InnerIterator row(Gt, mode.index()); row; ++row) {
      if (along[static_cast<size_t>(row.index())] == 0.0) reached.push_back(row.index());
      along[static_cast<size_t>(row.index())] += row.value() * mode.value();
    }
  std::sort(reached.begin(), reached.end());
  reached.erase(std::unique(reached.begin(), reached.end()), reached.end());
  out.clear();
  for (int k : reached) {
    out.emplace_back(k, along[static_cast<size_t>(k)]);
    along[static_cast<size_t>(k)] = 0.0;
  }
}

}  // namespace

Eigen::VectorXd FetiMethod::rigid_amplitudes() const {
  // alpha = (G^G^')^+ G^ (F lambda - d) = -(G^G^')^+ G^ r.
  Eigen::VectorXd alpha = -coarse_.amplitudes(r_);
  if (coarse_.unheld().empty()) return alpha;

  // A group the active rows leave free carries no load (else lambda would not balance
  // it): any translation that keeps its gaps open is a solution. Choose the one that
  // moves it least, i.e. keep it where it is unless a neighbour pushes it.
  // Linear in the groups: the displacements and B u are made once; moving a group by s
  // along z moves only its own subdomains (u += s R z there) and changes B u only on the
  // rows its modes reach (by s G'z), so each group costs its own rows and DOFs.
  const Decomposition& d = system_.decomposition();
  const DualSpace& space = system_.space();
  const Eigen::VectorXd u = system_.subdomain_displacements(lambda_, alpha, load_factor_);
  Eigen::VectorXd Bu;
  system_.apply_B(u, Bu);
  std::vector<double> along_rows(static_cast<size_t>(space.rows()), 0.0);
  std::vector<std::pair<int, double>> rate;  // (row, (G'z)_row) on the rows reached
  for (const UnheldGroup& group : coarse_.unheld()) {
    // Gap of every row the group reaches under the current placement, and its rate of
    // change per unit translation s along z: gap(s) = gap(0) - s (G'z)_k.
    reached_rows(Gt(), group.direction, along_rows, rate);
    double low = -std::numeric_limits<double>::infinity();
    double high = std::numeric_limits<double>::infinity();
    for (const auto& [r, g] : rate) {
      if (r < space.first_contact() || g == 0.0) continue;
      const double gap = std::max(0.0, system_.rhs()(r) - Bu(r));
      if (g > 0.0)
        high = std::min(high, gap / g);
      else
        low = std::max(low, gap / g);
    }
    low = space.max(low);
    high = -space.max(-high);
    // Displacement of the group per unit s, and the s that minimizes its norm (u is not
    // updated: no later group reads this group's DOFs).
    ExactSum sums[2];  // along, size: exact, so alike for any number of processes
    for (int j : group.subdomains) {
      const int i = system_.own_index(j);
      if (i < 0) continue;
      const Subdomain& sub = d.subdomains[j];
      Eigen::VectorXd amplitudes(sub.mode_count);
      for (int m = 0; m < sub.mode_count; ++m)
        amplitudes(m) = group.direction.coeff(sub.mode_offset + m);
      const Eigen::VectorXd motion = system_.subdomains()[i].R * amplitudes;
      const Eigen::VectorXd part = u.segment(system_.dof_offset(i), sub.dof_count);
      sums[0].merge(exact_dot(motion.data(), part.data(), motion.size()));
      sums[1].merge(exact_dot(motion.data(), motion.data(), motion.size()));
    }
    system_.communicator().sum(sums, 2);
    const double along = sums[0].value(), size = sums[1].value();
    const double s = size > 0.0 ? std::clamp(-along / size, std::min(low, high), high) : 0.0;
    alpha += s * group.direction;
    for (const auto& [r, g] : rate)
      Bu(r) += s * g;
  }
  return alpha;
}

ProcessProfile FetiMethod::profile() const {
  ProcessProfile p;
  const CommunicationStats& stats = system_.communicator().stats();
  p.subdomains = static_cast<int>(system_.subdomains().size());
  for (const SubdomainOperator& op : system_.subdomains())
    p.unknowns += system_.decomposition().subdomains[op.index].dof_count;
  p.rows = system_.rows();
  p.shared_rows = system_.space().shared_rows();
  p.f_applications = system_.f_applications();
  p.local_seconds = system_.times().local_solves;
  p.coarse_seconds = system_.times().coarse;
  p.preconditioner_seconds = system_.times().preconditioner;
  p.mode_product_seconds = system_.times().mode_products;
  p.range_projection_seconds = system_.times().range_projection;
  p.exchange_seconds = stats.exchange_seconds;
  p.reduction_seconds = stats.reduction_seconds;
  p.gather_seconds = stats.gather_seconds;
  p.communication = stats;
  p.coarse_size = coarse_.size();
  p.coarse_nonzeros = static_cast<long long>(coarse_.matrix_nonzeros());
  p.coarse_factorizations = coarse_.factorizations();
  p.coarse_updates = coarse_.updates();
  p.coarse_memory = coarse_.factor_memory();
  p.factor_memory = system_.factor_memory() + preconditioner_.factor_memory();
  p.memory = system_.memory();
  preconditioner_.add_memory(p.memory);
  p.setup = system_.setup_times();
  p.preconditioner_setup_seconds = preconditioner_.setup_seconds();
  p.coarse_setup_seconds = coarse_setup_seconds_;
  p.preconditioner_applications = preconditioner_.applications();
  p.f_bytes_read = system_.f_bytes_read();
  p.preconditioner_bytes_read = preconditioner_.bytes_read();
  return p;
}

void FetiMethod::update_residual(double a, const Eigen::VectorXd& q) {
  if (iteration_ % kResidualReplacement == 0)
    system_.residual(lambda_, load_factor_, r_);
  else
    r_ -= a * q;
}

void FetiMethod::reset_watch() {
  best_residual_ = std::numeric_limits<double>::infinity();
  best_iteration_ = 0;
}

void FetiMethod::watch_stagnation(double residual, int window) {
  if (residual < best_residual_) {
    best_residual_ = residual;
    best_iteration_ = iteration_;
  } else if (iteration_ - best_iteration_ >= window) {
    fail("stagnated: the relative residual has not gone below " + format_number(best_residual_) +
         " (iteration " + std::to_string(best_iteration_) + ") in " + std::to_string(window) +
         " iterations; the tolerance " + format_number(options_.tolerance) +
         " is probably below what rounding allows here");
  }
}

double FetiMethod::stopping_test(double norm) {
  const double residual = relative(norm);
  if (residual <= options_.tolerance || norm == 0.0)
    converge();
  else
    watch_stagnation(residual);
  return residual;
}

void FetiMethod::fail_breakdown(double yw, double pq) {
  fail(std::string(to_string(kind())) + " broke down at iteration " + std::to_string(iteration_) +
       ": the search direction has no curvature (y'w = " + format_number(yw) +
       ", p'F p = " + format_number(pq) + ") at relative residual " +
       format_number(history().empty() ? 0.0 : history().back().residual) +
       "; if that is tiny, the tolerance is below what rounding allows here");
}

void FetiMethod::fill_contacts(Snapshot& s) const {
  const Decomposition& d = system_.decomposition();
  const DualSpace& space = system_.space();
  const int pairs = static_cast<int>(model_.pairs.size());
  s.force.assign(pairs, 0.0);
  s.in_working_set.assign(pairs, 0);
  const bool any_rows = !history().empty();
  for (int k = 0; k < pairs; ++k) {
    const int row = d.pair_row[k];
    if (row < 0) continue;
    s.in_working_set[k] = coarse_.contact_active(row - d.equality_rows) ? 1 : 0;
    const int local = space.local_row(row);
    if (any_rows && local >= 0) s.force[k] = std::max(0.0, lambda_(local));
  }
}

Snapshot FetiMethod::snapshot() const {
  Snapshot s = snapshot_header();
  if (!history().empty()) {  // started (alike on every process)
    s.pieces = system_.pieces(lambda_, rigid_amplitudes(), load_factor_);
    s.dual = lambda_;
  }
  fill_contacts(s);
  return s;
}

namespace {

// Pieces as numbers for gathering: box index, strut, box, then per node (ux, uy) and in
// the frame model its rotation.
std::vector<double> pieces_as_numbers(const std::vector<Piece>& pieces,
                                      const std::vector<int>& piece_index, bool rotations) {
  std::vector<double> numbers;
  for (size_t i = 0; i < pieces.size(); ++i) {
    const Piece& piece = pieces[i];
    numbers.insert(numbers.end(),
                   {static_cast<double>(piece_index[i]), static_cast<double>(piece.strut),
                    static_cast<double>(piece.box.i0), static_cast<double>(piece.box.i1),
                    static_cast<double>(piece.box.k0), static_cast<double>(piece.box.k1)});
    for (size_t n = 0; n < piece.displacement.size(); ++n) {
      numbers.push_back(piece.displacement[n].x());
      numbers.push_back(piece.displacement[n].y());
      if (rotations) numbers.push_back(piece.rotation[n]);
    }
  }
  return numbers;
}

// The pieces of pieces_as_numbers put in their places in `whole`.
void place_pieces(const std::vector<double>& numbers, bool rotations, std::vector<Piece>& whole) {
  for (size_t at = 0; at < numbers.size();) {
    Piece& piece = whole[static_cast<size_t>(numbers[at])];
    piece.strut = static_cast<int>(numbers[at + 1]);
    piece.box = NodeBox{static_cast<int>(numbers[at + 2]), static_cast<int>(numbers[at + 3]),
                        static_cast<int>(numbers[at + 4]), static_cast<int>(numbers[at + 5])};
    at += 6;
    piece.displacement.resize(piece.box.node_count());
    if (rotations) piece.rotation.resize(piece.box.node_count());
    for (size_t n = 0; n < piece.displacement.size(); ++n) {
      piece.displacement[n] = Vec2(numbers[at], numbers[at + 1]);
      at += 2;
      if (rotations) piece.rotation[n] = numbers[at++];
    }
  }
}

}  // namespace

Snapshot FetiMethod::gathered(Snapshot s) const {
  const Communicator& comm = system_.communicator();
  if (!comm.distributed()) return s;
  const Decomposition& d = system_.decomposition();
  const DualSpace& space = system_.space();
  const bool rotations = model_.frame();
  std::vector<int> piece_index;
  for (const SubdomainOperator& op : system_.subdomains())
    for (const SubdomainPart& part : parts_of(d.subdomains[op.index], op.index))
      piece_index.push_back(part.piece);
  std::sort(piece_index.begin(), piece_index.end());  // the order of pieces()
  // Rank 0 moves its own pieces into the whole and takes the others' one process at a
  // time: it never holds the whole as numbers beside the whole as pieces (its peak
  // under mpirun, docs/DISTRIBUTED.md).
  std::vector<Piece> whole(comm.root() ? d.total_pieces : 0);
  std::vector<double> numbers;
  if (comm.root()) {
    for (size_t i = 0; i < s.pieces.size(); ++i)
      whole[static_cast<size_t>(piece_index[i])] = std::move(s.pieces[i]);
  } else {
    numbers = pieces_as_numbers(s.pieces, piece_index, rotations);
  }
  comm.gather_to_root_each(numbers, [&](int, const std::vector<double>& values) {
    place_pieces(values, rotations, whole);
  });
  // Per owned pair row: the pair, its force and its working-set flag (FETI-C knows every
  // pair's flag, MPRGP only its own rows').
  std::vector<double> forces;
  for (size_t k = 0; k < s.force.size(); ++k) {
    const int row = d.pair_row[k];
    if (row < 0) continue;
    const int local = space.local_row(row);
    if (local >= 0 && space.owned(local)) {
      forces.push_back(static_cast<double>(k));
      forces.push_back(s.force[k]);
      forces.push_back(s.in_working_set[k]);
    }
  }
  const std::vector<double> all_forces = comm.gather_to_root(forces);
  s.dual.resize(0);  // the multipliers stay distributed
  if (!comm.root()) return s;
  s.pieces = std::move(whole);
  for (size_t at = 0; at + 2 < all_forces.size(); at += 3) {
    const auto k = static_cast<size_t>(all_forces[at]);
    s.force[k] = all_forces[at + 1];
    s.in_working_set[k] = all_forces[at + 2] != 0.0 ? 1 : 0;
  }
  return s;
}

double FetiMethod::reference_error() const {
  // Rank 0 compares the whole state; every process records the same number.
  const Snapshot whole = gathered_snapshot();
  double error = 0.0;
  if (system_.communicator().root())
    error = relative_error(strut_displacements(model_, whole), reference());
  system_.communicator().broadcast(error);
  return error;
}

FetiMethod::PcpgStep FetiMethod::pcpg_step(const Eigen::VectorXd& w, const std::vector<char>* face,
                                           bool restart, double yw_previous, Eigen::VectorXd& p,
                                           Eigen::VectorXd& q) {
  Eigen::VectorXd y;
  preconditioner_.apply(w, face, y);
  system_.project_onto_range_of_B(y);
  coarse_.project(y);
  const double yw = space().dot(y, w);
  const double beta = restart || !(yw_previous > 0.0) ? 0.0 : yw / yw_previous;
  if (iteration_ == 0) condition_.clear();
  if (beta == 0.0) condition_.restart();
  p = restart ? y : Eigen::VectorXd(y + beta * p);
  system_.apply_F(p, q);
  const double pq = space().dot(p, q);
  ++iteration_;
  if (!(pq > 0.0) || !(yw > 0.0)) {
    fail_breakdown(yw, pq);
    return {};
  }
  condition_.add(yw / pq, beta);
  return {yw / pq, yw, true};
}

}  // namespace fetic::solver
