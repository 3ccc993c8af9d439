#include "solver/contact_coarse.hpp"

#include <algorithm>
#include <limits>
#include <map>
#include <tuple>
#include <unordered_map>

#include <Eigen/Eigenvalues>

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
  // W = A U, kept on the rows where it does not vanish (the clusters a column touches).
  W_.resize(next);
  Eigen::VectorXd u, w;
  for (int c = 0; c < next; ++c) {
    u.setZero(space.rows());
    for (size_t i = 0; i < U_[c].rows.size(); ++i)
      u(U_[c].rows[i]) = U_[c].values[i];
    apply_A(u, w);
    for (int k = 0; k < space.rows(); ++k)
      if (w(k) != 0.0) {
        W_[c].rows.push_back(k);
        W_[c].values.push_back(w(k));
      }
  }
  // E = U'W, symmetrized; its pseudo-inverse (a segment whose rows all coincide with
  // another's would make it singular).
  Eigen::MatrixXd E(next, next);
  for (int c = 0; c < next; ++c) {
    Eigen::VectorXd wc = Eigen::VectorXd::Zero(space.rows());
    for (size_t i = 0; i < W_[c].rows.size(); ++i)
      wc(W_[c].rows[i]) = W_[c].values[i];
    E.col(c) = dots(U_, wc);
  }
  E = 0.5 * (E + E.transpose()).eval();
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(E);
  Eigen::VectorXd inverse = eigen.eigenvalues();
  const double top = next > 0 ? inverse.cwiseAbs().maxCoeff() : 0.0;
  for (int i = 0; i < next; ++i)
    inverse(i) = inverse(i) > 1e-12 * top ? 1.0 / inverse(i) : 0.0;
  E_inverse_ = eigen.eigenvectors() * inverse.asDiagonal() * eigen.eigenvectors().transpose();
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
  const Eigen::VectorXd coarse = E_inverse_ * dots(U_, g);  // E^-1 U'g
  Eigen::VectorXd g1 = g;
  add(W_, -coarse, g1);  // (I - W E^-1 U') g, then back on the face
  for (int k = 0; k < g1.size(); ++k)
    if (!free[k]) g1(k) = 0.0;
  inner(g1, free, z);
  add(U_, -(E_inverse_ * dots(W_, z)) + coarse, z);
  for (int k = 0; k < z.size(); ++k)
    if (!free[k]) z(k) = 0.0;
}

}  // namespace fetic::solver
