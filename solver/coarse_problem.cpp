#include "solver/coarse_problem.hpp"

#include <algorithm>
#include <cmath>
#include <queue>
#include <stdexcept>

#include "solver/free_motion_space.hpp"
#include "solver/interruption.hpp"
#include "solver/stopwatch.hpp"
#include "solver/threads.hpp"

namespace fetic::solver {
namespace {

// Rows a factor may be updated by before it is factorized from scratch (rounding of the
// updates accumulates; a full factorization resets it).
constexpr int kRowsBetweenFactorizations = 64;

}  // namespace

CoarseProblem::CoarseProblem(const FetiSystem& system) : system_(system) {
  const Decomposition& d = system.decomposition();
  contact_active_.assign(d.contact_rows(), 1);
  active_.assign(system.rows(), 1);
  build_pattern();
  if (system.model().frame()) frame_motions_ = std::make_shared<const FreeMotionSpace>(system);
}

CoarseProblem::CoarseProblem(const CoarseProblem& other, SamePattern)
    : system_(other.system_),
      active_(other.active_.size(), 1),
      contact_active_(other.contact_active_.size(), 1),
      pattern_(other.pattern_),
      own_values_(other.pattern_->own_values, 0.0),
      matrix_(other.matrix_),
      frame_motions_(other.frame_motions_) {}

namespace {

// The local rows B_j touches, each once (its incidence is by row).
std::vector<int> rows_of(const SubdomainOperator& op) {
  std::vector<int> rows;
  for (const Incidence& in : op.incidence)
    if (rows.empty() || rows.back() != in.row) rows.push_back(in.row);
  return rows;
}

bool own_mode(const Subdomain& sub, Eigen::Index mode) {
  return mode >= sub.mode_offset && mode < sub.mode_offset + sub.mode_count;
}

}  // namespace

// One own subdomain's block rows of G G': its entries (a, b), sorted and each once.
std::vector<std::pair<int, int>> CoarseProblem::own_entries(const SubdomainOperator& op,
                                                            const Subdomain& sub) const {
  const SparseMatrix& G = system_.G();
  std::vector<std::pair<int, int>> entries;
  for (int r : rows_of(op))
    for (SparseMatrix::InnerIterator a(G, r); a; ++a) {
      if (!own_mode(sub, a.row())) continue;
      for (SparseMatrix::InnerIterator b(G, r); b; ++b)
        entries.emplace_back(static_cast<int>(a.row()), static_cast<int>(b.row()));
    }
  std::sort(entries.begin(), entries.end());
  entries.erase(std::unique(entries.begin(), entries.end()), entries.end());
  return entries;
}

// Per local row the subdomain touches, its products g_a g_b, written from `product` and
// `row` on; their values numbered from `first_value` in the order of `entries`.
void CoarseProblem::write_products(const SubdomainOperator& op, const Subdomain& sub,
                                   const std::vector<std::pair<int, int>>& entries, int first_value,
                                   Product* product, RowProducts* row, int first_product) const {
  const SparseMatrix& G = system_.G();
  int next = first_product;
  for (int r : rows_of(op)) {
    RowProducts rp{r, next, next};
    int ia = 0;
    for (SparseMatrix::InnerIterator a(G, r); a; ++a, ++ia) {
      if (!own_mode(sub, a.row())) continue;
      int ib = 0;
      for (SparseMatrix::InnerIterator b(G, r); b; ++b, ++ib) {
        const std::pair<int, int> ab{static_cast<int>(a.row()), static_cast<int>(b.row())};
        const auto at = std::lower_bound(entries.begin(), entries.end(), ab);
        *product++ = {first_value + static_cast<int>(at - entries.begin()), ia, ib};
        ++next;
      }
    }
    rp.end = next;
    *row++ = rp;
  }
}

// Per own subdomain, its products and rows (as write_products() lays them out), counted.
void CoarseProblem::count_products(std::vector<int>& products, std::vector<int>& rows) const {
  const SparseMatrix& G = system_.G();
  const Decomposition& d = system_.decomposition();
  const auto& ops = system_.subdomains();
  const int count = static_cast<int>(ops.size());
  products.assign(static_cast<std::size_t>(count) + 1, 0);
  rows.assign(static_cast<std::size_t>(count) + 1, 0);
  long long work = 0;
  for (const SubdomainOperator& op : ops)
    work += static_cast<long long>(op.incidence.size());
#pragma omp parallel for schedule(dynamic, 16) num_threads(threads_for(work))
  for (int i = 0; i < count; ++i) {
    const Subdomain& sub = d.subdomains[ops[i].index];
    int previous = -1;
    for (const Incidence& in : ops[i].incidence) {
      if (in.row == previous) continue;  // incidence is by row
      previous = in.row;
      const int column = G.outerIndexPtr()[in.row + 1] - G.outerIndexPtr()[in.row];
      int own = 0;
      for (SparseMatrix::InnerIterator a(G, in.row); a; ++a)
        own += own_mode(sub, a.row());
      products[i + 1] += own * column;
      ++rows[i + 1];
    }
  }
}

// The block rows of G G' this process computes: for own subdomain j, the sum over the
// rows r touching j of g_r(modes of j) g_r', in increasing r (the same order on every
// number of processes). Values are laid out per own subdomain, entries (a, b) sorted.
// Every subdomain's entries, then (their numbers counted) its products, are found on
// both cores and written where they belong: only counts are joined in turn (the joined
// products, about 36 per local row, were copied in a serial pass).
void CoarseProblem::build_pattern() {
  const FetiSystem& s = system_;
  const Decomposition& d = s.decomposition();
  const Communicator& comm = s.communicator();
  const auto& ops = s.subdomains();
  const int count = static_cast<int>(ops.size());
  auto built = std::make_shared<Pattern>();
  std::vector<int> products, rows;
  count_products(products, rows);
  std::vector<std::vector<std::pair<int, int>>> entries(static_cast<std::size_t>(count));
  std::vector<int> values(static_cast<std::size_t>(count) + 1, 0);
  long long work = 0;
  for (const SubdomainOperator& op : ops)
    work += static_cast<long long>(op.incidence.size()) * 10;
#pragma omp parallel for schedule(dynamic, 4) num_threads(threads_for(work))
  for (int i = 0; i < count; ++i) {
    if (stop_requested()) continue;  // Ctrl-C: skip the rest (no throw inside OpenMP)
    entries[i] = own_entries(ops[i], d.subdomains[ops[i].index]);
    values[i + 1] = static_cast<int>(entries[i].size());
  }
  throw_if_stopped("assembling the coarse problem");
  for (int i = 0; i < count; ++i) {
    products[i + 1] += products[i];
    rows[i + 1] += rows[i];
    values[i + 1] += values[i];
  }
  built->products.resize(static_cast<std::size_t>(products[count]));
  built->row_products.resize(static_cast<std::size_t>(rows[count]));
  built->own_values = static_cast<std::size_t>(values[count]);
  std::vector<int> pattern(2 * built->own_values);  // (a, b) pairs, in value order
#pragma omp parallel for schedule(dynamic, 4) num_threads(threads_for(work))
  for (int i = 0; i < count; ++i) {
    write_products(ops[i], d.subdomains[ops[i].index], entries[i], values[i],
                   built->products.data() + products[i], built->row_products.data() + rows[i],
                   products[i]);
    for (std::size_t k = 0; k < entries[i].size(); ++k) {
      pattern[2 * (values[i] + k)] = entries[i][k].first;
      pattern[2 * (values[i] + k) + 1] = entries[i][k].second;
    }
  }

  // The whole pattern, gathered once; the lower triangle becomes the matrix.
  const std::vector<int> all = comm.all_gather(pattern);
  const int n = d.total_modes;
  std::vector<Eigen::Triplet<double>> lower;
  for (size_t k = 0; k + 1 < all.size(); k += 2)
    if (all[k] >= all[k + 1]) lower.emplace_back(all[k], all[k + 1], 1.0);
  matrix_.resize(n, n);
  matrix_.setFromTriplets(lower.begin(), lower.end());
  matrix_.makeCompressed();
  built->value_slot.assign(all.size() / 2, -1);
  for (size_t k = 0; k + 1 < all.size(); k += 2) {
    const int a = all[k], b = all[k + 1];
    if (a < b) continue;
    // Position of (a, b) in column b of the compressed lower triangle.
    const int* begin = matrix_.innerIndexPtr() + matrix_.outerIndexPtr()[b];
    const int* end = matrix_.innerIndexPtr() + matrix_.outerIndexPtr()[b + 1];
    built->value_slot[k / 2] =
        static_cast<int>(std::lower_bound(begin, end, a) - matrix_.innerIndexPtr());
  }
  own_values_.assign(built->own_values, 0.0);
  pattern_ = std::move(built);
}

bool CoarseProblem::row_active(int global_row) const {
  const int first_contact = system_.decomposition().equality_rows;
  return global_row < first_contact || contact_active_[global_row - first_contact] != 0;
}

bool CoarseProblem::set_active_rows(const std::vector<char>& active) {
  const FetiSystem& s = system_;
  const DualSpace& space = s.space();
  const int first_contact = s.decomposition().equality_rows;
  // The owned contact rows whose flag changed, from every process.
  std::vector<int> changes;
  for (int r = space.first_contact(); r < space.rows(); ++r) {
    if (!space.owned(r)) continue;
    const int k = space.global_row(r) - first_contact;
    const char flag = active[r] ? 1 : 0;
    if (flag != contact_active_[k]) changes.push_back(flag ? k + 1 : -(k + 1));
  }
  const std::vector<int> all = s.communicator().all_gather(changes);
  for (int change : all)
    contact_active_[std::abs(change) - 1] = change > 0 ? 1 : 0;
  for (int r = 0; r < space.rows(); ++r)
    active_[r] = row_active(space.global_row(r)) ? 1 : 0;
  if (all.empty() && factorized_) return false;
  if (!factorized_ || !update_factor(changes, all.size())) factorize();
  return true;
}

// The factor of the new G^ G^' from the old one: + g g' for each row that entered, - g g'
// for each that left, g its column of G (from the row's owner). False, with nothing
// changed, when the factor cannot be updated; false after a failed update too (the
// caller then factorizes from scratch, which reanalyses).
bool CoarseProblem::update_factor(const std::vector<int>& own_changes, std::size_t all_changes) {
  if (!updatable_ || rows_updated_ + static_cast<int>(all_changes) > kRowsBetweenFactorizations)
    return false;
  find_unheld_groups();
  if (!unheld_.empty() || !pinned_.empty()) return false;
  Stopwatch watch(system_.times().coarse);
  const FetiSystem& s = system_;
  const DualSpace& space = s.space();
  const SparseMatrix& G = s.G();
  const int first_contact = s.decomposition().equality_rows;
  // Per changed owned row: its signed change, its number of entries, then (mode, value).
  std::vector<double> own;
  for (int change : own_changes) {
    const int local = space.local_row(first_contact + std::abs(change) - 1);
    own.push_back(change);
    own.push_back(static_cast<double>(G.col(local).nonZeros()));
    for (SparseMatrix::InnerIterator it(G, local); it; ++it) {
      own.push_back(static_cast<double>(it.row()));
      own.push_back(it.value());
    }
  }
  const std::vector<double> all = s.communicator().all_gather(own);
  std::vector<Eigen::Triplet<double>> entered, left;
  int entered_columns = 0, left_columns = 0;
  for (std::size_t at = 0; at < all.size();) {
    const bool enters = all[at] > 0.0;
    const int count = static_cast<int>(all[at + 1]);
    at += 2;
    const int column = enters ? entered_columns++ : left_columns++;
    for (int e = 0; e < count; ++e, at += 2)
      (enters ? entered : left).emplace_back(static_cast<int>(all[at]), column, all[at + 1]);
  }
  const int n = system_.modes();
  SparseMatrix add(n, entered_columns), remove(n, left_columns);
  add.setFromTriplets(entered.begin(), entered.end());
  remove.setFromTriplets(left.begin(), left.end());
  add.makeCompressed();
  remove.makeCompressed();
  reanalyse_ = true;  // the factor is a simplicial LDL' from here on
  // Rows in first, so that every intermediate matrix stays positive definite.
  if (factor_.update(add, true) != CholmodFactor::Result::Ok) return false;
  if (factor_.update(remove, false) != CholmodFactor::Result::Ok) return false;
  rows_updated_ += static_cast<int>(all_changes);
  ++updates_;
  return true;
}

void CoarseProblem::factorize() {
  Stopwatch watch(system_.times().coarse);
  const SparseMatrix& G = system_.G();
  const Pattern& pattern = *pattern_;
  std::fill(own_values_.begin(), own_values_.end(), 0.0);
  for (const RowProducts& rp : pattern.row_products) {
    if (!active_[rp.row]) continue;
    const double* column = G.valuePtr() + G.outerIndexPtr()[rp.row];
    for (int p = rp.first; p < rp.end; ++p) {
      const Product& product = pattern.products[p];
      own_values_[product.value] += column[product.a] * column[product.b];
    }
  }
  const std::vector<double> all = system_.communicator().all_gather(own_values_);
  std::fill(matrix_.valuePtr(), matrix_.valuePtr() + matrix_.nonZeros(), 0.0);
  for (size_t k = 0; k < all.size(); ++k)
    if (pattern.value_slot[k] >= 0) matrix_.valuePtr()[pattern.value_slot[k]] = all[k];
  ++factorizations_;
  factorized_ = true;

  find_unheld_groups();
  const std::vector<UnheldGroup>& pins = pinned_.empty() ? unheld_ : pinned_;
  if (pins.empty()) {
    // The analysis of the fixed pattern is kept unless the last factor had extra entries.
    const CholmodFactor::Result result =
        reanalyse_ ? factor_.factorize(matrix_) : factor_.refactorize(matrix_);
    reanalyse_ = false;
    updatable_ = true;
    rows_updated_ = 0;
    if (result == CholmodFactor::Result::Ok) return;
  } else {
    // Pin each free direction: G^ G^' + z z' (outside the fixed pattern, so analysed anew).
    const Decomposition& d = system_.decomposition();
    std::vector<Eigen::Triplet<double>> extra;
    for (const UnheldGroup& group : pins) {
      const Eigen::SparseVector<double>& z = group.direction;
      for (int a : group.subdomains)
        for (int b : group.subdomains) {
          // Every mode of both (one per subdomain in the bar model, three in the frame
          // model); the lower triangle only.
          const Subdomain& sa = d.subdomains[a];
          const Subdomain& sb = d.subdomains[b];
          for (int ma = sa.mode_offset; ma < sa.mode_offset + sa.mode_count; ++ma)
            for (int mb = sb.mode_offset; mb < sb.mode_offset + sb.mode_count; ++mb)
              if (ma >= mb) extra.emplace_back(ma, mb, z.coeff(ma) * z.coeff(mb));
        }
    }
    SparseMatrix Z(matrix_.rows(), matrix_.cols());
    Z.setFromTriplets(extra.begin(), extra.end());
    SparseMatrix A = matrix_ + Z;
    A.makeCompressed();
    reanalyse_ = true;
    updatable_ = false;
    if (factor_.factorize(A) == CholmodFactor::Result::Ok) return;
  }
  throw SolverError(
      "the coarse problem G G' is singular: a group of subdomains is held by no active row "
      "in a way the solver cannot resolve");
}

double CoarseProblem::g(int global_row, int subdomain) const {
  double value = 0.0;
  for (const RowEntry& entry : system_.decomposition().rows[global_row].entries)
    if (entry.subdomain == subdomain) value += entry.value;  // bar: R = 1
  return value;
}

// Bar model: subdomains linked by active rows form groups; a group containing no
// Dirichlet row can translate along its axis. Its direction z solves g_a z_a + g_b z_b = 0
// for every active row between subdomains a and b (g: the row's column of G). Computed
// from the replicated decomposition and working set, so alike on every process.
void CoarseProblem::find_unheld_groups() {
  unheld_.clear();
  if (frame_motions_) {
    unheld_ = frame_motions_->unheld(contact_active_);
    return;
  }
  const Decomposition& d = system_.decomposition();
  if (system_.model().dofs_per_node() != 1) return;  // plane struts are always clamped
  const int count = static_cast<int>(d.subdomains.size());
  std::vector<std::vector<int>> rows_of(count);
  for (int r = 0; r < d.row_count(); ++r)
    if (row_active(r))
      for (const RowEntry& entry : d.rows[r].entries)
        rows_of[entry.subdomain].push_back(r);
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
      if (d.subdomains[a].mode_count == 0) held = true;  // FETI-DP: a clamp made primal
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
    std::vector<std::pair<int, double>> entries;
    for (int s : group.subdomains)
      entries.emplace_back(d.subdomains[s].mode_offset, value[s]);
    std::sort(entries.begin(), entries.end());
    group.direction.resize(d.total_modes);
    group.direction.reserve(static_cast<Eigen::Index>(entries.size()));
    for (const auto& [mode, amplitude] : entries)
      group.direction.insertBack(mode) = amplitude;
    group.direction /= group.direction.norm();
    unheld_.push_back(std::move(group));
  }
}

Eigen::VectorXd CoarseProblem::solve(const Eigen::VectorXd& b) const {
  Stopwatch watch(system_.times().coarse);
  Eigen::VectorXd x(b.size());
  factor_.solve(b.data(), x.data());
  return x;
}

Eigen::VectorXd CoarseProblem::apply_G(const Eigen::VectorXd& v) const {
  return system_.apply_G(v, &active_);
}

Eigen::VectorXd CoarseProblem::apply_Gt(const Eigen::VectorXd& a) const {
  Stopwatch watch(system_.times().mode_products);
  Eigen::VectorXd out = system_.G().transpose() * a;
  for (int r = 0; r < out.size(); ++r)
    if (!active_[r]) out(r) = 0.0;
  return out;
}

void CoarseProblem::project(Eigen::VectorXd& v) const {
  subtract_Gt(solve(apply_G(v)), v);  // in place: no vector over the rows made
}

Eigen::VectorXd CoarseProblem::particular(const Eigen::VectorXd& e) const {
  return apply_Gt(solve(e));
}

Eigen::VectorXd CoarseProblem::amplitudes(const Eigen::VectorXd& r) const {
  return solve(apply_G(r));
}

}  // namespace fetic::solver
