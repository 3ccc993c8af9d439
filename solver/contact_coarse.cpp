#include "solver/contact_coarse.hpp"

#include <algorithm>
#include <limits>
#include <map>
#include <tuple>
#include <unordered_map>

#include <Eigen/Eigenvalues>

#include "solver/contact_batches.hpp"
#include "solver/exact_sum.hpp"

namespace fetic::solver {
namespace {

// The box (decompose()'s piece) holding an entry's DOF; a DOF some boxes of a cluster
// share (a corner) goes to the lowest of them. Maps built only for the subdomains asked.
class PieceOfDof {
 public:
  explicit PieceOfDof(const Decomposition& d) : d_(d) {}
  int operator()(const RowEntry& e) {
    auto found = maps_.find(e.subdomain);
    if (found == maps_.end()) found = maps_.emplace(e.subdomain, build(e.subdomain)).first;
    return found->second[e.dof];
  }

 private:
  std::vector<int> build(int s) const {
    const Subdomain& sub = d_.subdomains[s];
    std::vector<int> piece(sub.dof_count, std::numeric_limits<int>::max());
    for (const SubdomainPart& part : parts_of(sub, s)) {
      if (part.dofs.empty()) {
        for (int& p : piece)
          p = std::min(p, part.piece);
        continue;
      }
      for (int dof : part.dofs)
        piece[dof] = std::min(piece[dof], part.piece);
    }
    return piece;
  }

  const Decomposition& d_;
  std::unordered_map<int, std::vector<int>> maps_;
};

// Per contact row of the whole decomposition: its segment (contact, box a, box b) and its
// coordinate along the face (the pair's index: pairs are numbered along t).
struct Segments {
  std::vector<int> of_row;  // per global contact row (from d.equality_rows), its segment
  std::vector<double> coordinate;
  std::vector<double> low, high, mean;  // per segment, of the coordinates
  std::vector<char> floating;           // per segment: a cluster it touches has modes in G
};

Segments find_segments(const Model& model, const Decomposition& d) {
  Segments s;
  PieceOfDof piece_of(d);
  std::map<std::tuple<int, int, int>, int> index;
  std::vector<double> sum, count;
  for (int r = d.equality_rows; r < d.row_count(); ++r) {
    const Row& row = d.rows[r];
    const ContactPair& pair = model.pairs[row.pair];
    const int a = row.entries.empty() ? -1 : piece_of(row.entries.front());
    const int b = row.entries.size() < 2 ? -1 : piece_of(row.entries.back());
    const auto key = std::make_tuple(pair.contact, a, b);
    auto found = index.find(key);
    if (found == index.end()) {
      found = index.emplace(key, static_cast<int>(index.size())).first;
      s.low.push_back(std::numeric_limits<double>::max());
      s.high.push_back(std::numeric_limits<double>::lowest());
      sum.push_back(0.0);
      count.push_back(0.0);
      s.floating.push_back(0);
    }
    const int g = found->second;
    for (const RowEntry& e : row.entries)
      if (d.subdomains[e.subdomain].mode_count > 0) s.floating[g] = 1;
    const double t = pair.pair;
    s.of_row.push_back(g);
    s.coordinate.push_back(t);
    s.low[g] = std::min(s.low[g], t);
    s.high[g] = std::max(s.high[g], t);
    sum[g] += t;
    count[g] += 1.0;
  }
  for (size_t g = 0; g < sum.size(); ++g)
    s.mean.push_back(sum[g] / count[g]);
  return s;
}

}  // namespace

ContactCoarseSpace::ContactCoarseSpace(const FetiSystem& system, const Operator& apply_A,
                                       bool clamped_only)
    : space_(&system.space()) {
  const Decomposition& d = system.decomposition();
  const Segments s = find_segments(system.model(), d);
  // Column numbers from the replicated segments: uniform, then linear where a segment has
  // two or more coordinates - the same on every process.
  const int segments = static_cast<int>(s.mean.size());
  std::vector<int> uniform(segments, -1), linear(segments, -1);
  int next = 0;
  for (int g = 0; g < segments; ++g) {
    if (clamped_only && s.floating[g]) continue;
    uniform[g] = next++;
    if (s.high[g] > s.low[g]) linear[g] = next++;
  }
  if (next == 0) return;  // no segment qualifies: no coarse space (the caller drops it)
  U_.resize(next);
  std::vector<std::vector<int>> column_rows(next);  // global, for the batches
  for (int r = d.equality_rows; r < d.row_count(); ++r) {
    const int g = s.of_row[r - d.equality_rows];
    if (uniform[g] < 0) continue;  // a segment without columns
    column_rows[uniform[g]].push_back(r);
    if (linear[g] >= 0) column_rows[linear[g]].push_back(r);
  }
  const DualSpace& space = *space_;
  for (int k = space.first_contact(); k < space.rows(); ++k) {
    const int c = space.global_row(k) - d.equality_rows;
    const int g = s.of_row[c];
    if (uniform[g] < 0) continue;
    U_[uniform[g]].rows.push_back(k);
    U_[uniform[g]].values.push_back(1.0);
    if (linear[g] < 0) continue;
    U_[linear[g]].rows.push_back(k);
    U_[linear[g]].values.push_back((s.coordinate[c] - s.mean[g]) / (s.high[g] - s.low[g]));
  }
  const ContactBatches plan = batch_columns(d, column_rows);
  form_W(d, plan, apply_A);
  form_E_inverse(plan.components);
}

// W = A U, batch by batch: each column keeps the nonzeros of A's result on the rows that
// touch its blocks (contact_batches.hpp), the rows where A u_c does not vanish.
void ContactCoarseSpace::form_W(const Decomposition& d, const ContactBatches& plan,
                                const Operator& apply_A) {
  const DualSpace& space = *space_;
  W_.assign(U_.size(), Column{});
  std::vector<int> owner(plan.block_count, -1);
  const auto owner_of_row = [&](int k) {
    for (const RowEntry& e : d.rows[space.global_row(k)].entries) {
      const int c = owner[plan.block_of_subdomain[e.subdomain]];
      if (c >= 0) return c;
    }
    return -1;
  };
  double stray = 0.0;  // nonzeros outside every reach: A's support misjudged
  Eigen::VectorXd u, w;
  for (const std::vector<int>& batch : plan.batches) {
    u.setZero(space.rows());
    for (int c : batch) {
      for (size_t i = 0; i < U_[c].rows.size(); ++i)
        u(U_[c].rows[i]) += U_[c].values[i];
      for (int b : plan.column_blocks[c])
        owner[b] = c;
    }
    apply_A(u, w);
    ++applications_;
    for (int k = 0; k < space.rows(); ++k) {
      if (w(k) == 0.0) continue;
      const int c = owner_of_row(k);
      if (c < 0) {
        stray += 1.0;
        continue;
      }
      W_[c].rows.push_back(k);
      W_[c].values.push_back(w(k));
    }
    for (int c : batch)
      for (int b : plan.column_blocks[c])
        owner[b] = -1;
  }
  if (space.communicator().max(stray) > 0.0)
    throw SolverError(
        "internal error: the contact faces' coarse space found A u nonzero "
        "outside the blocks of u's rows (solver/contact_batches.hpp)");
}

// E = U'W block by block over the components (exact sums, a bounded number of them reduced
// at a time), symmetrized; each block's pseudo-inverse (a segment whose rows all coincide
// with another's would make it singular), with one threshold relative to all of E.
void ContactCoarseSpace::form_E_inverse(const std::vector<std::vector<int>>& components) {
  const DualSpace& space = *space_;
  const int columns = static_cast<int>(U_.size());
  std::vector<int> component_of(columns), position(columns);
  for (size_t m = 0; m < components.size(); ++m)
    for (size_t i = 0; i < components[m].size(); ++i) {
      component_of[components[m][i]] = static_cast<int>(m);
      position[components[m][i]] = static_cast<int>(i);
    }
  // The columns of U on each local row: (column, value).
  std::vector<std::vector<std::pair<int, double>>> on_row(space.rows() - space.first_contact());
  for (int c = 0; c < columns; ++c)
    for (size_t i = 0; i < U_[c].rows.size(); ++i)
      on_row[U_[c].rows[i] - space.first_contact()].emplace_back(c, U_[c].values[i]);
  std::vector<Eigen::MatrixXd> E(components.size());
  for (size_t m = 0; m < components.size(); ++m)
    E[m].setZero(components[m].size(), components[m].size());
  constexpr size_t kChunk = 4096;  // exact sums reduced at once (about 600 bytes each)
  std::vector<ExactSum> sums;
  std::vector<int> pending;  // columns j whose sums are in `sums`, in order
  double stray = 0.0;
  const auto flush = [&] {
    space.communicator().sum(sums.data(), static_cast<int>(sums.size()));
    size_t at = 0;
    for (int j : pending) {
      Eigen::MatrixXd& block = E[component_of[j]];
      for (Eigen::Index i = 0; i < block.rows(); ++i)
        block(i, position[j]) = sums[at++].value();
    }
    sums.clear();
    pending.clear();
  };
  for (const std::vector<int>& component : components)
    for (int j : component) {
      const size_t n = component.size();
      if (!pending.empty() && sums.size() + n > kChunk) flush();
      const size_t offset = sums.size();
      sums.resize(offset + n);
      pending.push_back(j);
      for (size_t i = 0; i < W_[j].rows.size(); ++i) {
        const int k = W_[j].rows[i];
        if (k < space.first_contact() || !space.owned(k)) continue;
        for (const auto& [c, value] : on_row[k - space.first_contact()]) {
          if (component_of[c] != component_of[j]) {
            stray += 1.0;
            continue;
          }
          sums[offset + position[c]].add(value * W_[j].values[i]);
        }
      }
    }
  if (!pending.empty()) flush();
  if (space.communicator().max(stray) > 0.0)
    throw SolverError(
        "internal error: the contact faces' coarse space found E coupling "
        "columns of no shared block (solver/contact_batches.hpp)");
  invert_blocks(components, E);
}

void ContactCoarseSpace::invert_blocks(const std::vector<std::vector<int>>& components,
                                       std::vector<Eigen::MatrixXd>& E) {
  std::vector<Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>> eigen;
  double top = 0.0;
  for (Eigen::MatrixXd& block : E) {
    block = 0.5 * (block + block.transpose()).eval();
    eigen.emplace_back(block);
    top = std::max(top, eigen.back().eigenvalues().cwiseAbs().maxCoeff());
  }
  blocks_.clear();
  for (size_t m = 0; m < E.size(); ++m) {
    Eigen::VectorXd inverse = eigen[m].eigenvalues();
    for (Eigen::Index i = 0; i < inverse.size(); ++i)
      inverse(i) = inverse(i) > 1e-12 * top ? 1.0 / inverse(i) : 0.0;
    const Eigen::MatrixXd& V = eigen[m].eigenvectors();
    blocks_.push_back(Block{components[m], V * inverse.asDiagonal() * V.transpose()});
  }
}

Eigen::VectorXd ContactCoarseSpace::solve_E(const Eigen::VectorXd& y) const {
  Eigen::VectorXd x(y.size());
  for (const Block& block : blocks_) {
    const Eigen::Index n = static_cast<Eigen::Index>(block.columns.size());
    Eigen::VectorXd part(n);
    for (Eigen::Index i = 0; i < n; ++i)
      part(i) = y(block.columns[i]);
    part = (block.inverse * part).eval();
    for (Eigen::Index i = 0; i < n; ++i)
      x(block.columns[i]) = part(i);
  }
  return x;
}

Eigen::VectorXd ContactCoarseSpace::dots(const std::vector<Column>& C,
                                         const Eigen::VectorXd& v) const {
  std::vector<ExactSum> sums(C.size());
  for (size_t c = 0; c < C.size(); ++c)
    for (size_t i = 0; i < C[c].rows.size(); ++i)
      if (space_->owned(C[c].rows[i])) sums[c].add(C[c].values[i] * v(C[c].rows[i]));
  space_->communicator().sum(sums.data(), static_cast<int>(sums.size()));
  Eigen::VectorXd out(C.size());
  for (size_t c = 0; c < C.size(); ++c)
    out(c) = sums[c].value();
  return out;
}

void ContactCoarseSpace::add(const std::vector<Column>& C, const Eigen::VectorXd& c,
                             Eigen::VectorXd& v) {
  for (size_t j = 0; j < C.size(); ++j)
    for (size_t i = 0; i < C[j].rows.size(); ++i)
      v(C[j].rows[i]) += c(j) * C[j].values[i];
}

void ContactCoarseSpace::apply(const Eigen::VectorXd& g, const std::vector<char>& free,
                               const FacePreconditioner& inner, Eigen::VectorXd& z) const {
  const Eigen::VectorXd coarse = solve_E(dots(U_, g));  // E^-1 U'g
  Eigen::VectorXd g1 = g;
  add(W_, -coarse, g1);  // (I - W E^-1 U') g, then back on the face
  for (int k = 0; k < g1.size(); ++k)
    if (!free[k]) g1(k) = 0.0;
  inner(g1, free, z);
  add(U_, -solve_E(dots(W_, z)) + coarse, z);
  for (int k = 0; k < z.size(); ++k)
    if (!free[k]) z(k) = 0.0;
}

}  // namespace fetic::solver
