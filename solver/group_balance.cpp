#include "solver/group_balance.hpp"

#include <algorithm>
#include <string>

#include <Eigen/SparseCore>

#include "scenes/union_find.hpp"
#include "solver/exact_sum.hpp"
#include "solver/interruption.hpp"
#include "solver/method.hpp"

namespace fetic::solver {
namespace {

// Groups handled between two polls for an interrupt.
constexpr size_t kPollEvery = 64;

std::vector<double> values_of(std::vector<ExactSum>& sums, const Communicator& communicator) {
  communicator.sum(sums.data(), static_cast<int>(sums.size()));
  std::vector<double> values(sums.size());
  for (size_t i = 0; i < sums.size(); ++i)
    values[i] = sums[i].value();
  return values;
}

}  // namespace

GroupBalance::GroupBalance(const FetiSystem& system, const std::vector<UnheldGroup>& groups)
    : space_(&system.space()) {
  keep_groups_with_contacts(system, groups);
  factorize_blocks();
}

// c = G'z on the contact rows, found through the modes z moves: linear in the group's
// size, not in the whole coarse space.
void GroupBalance::keep_groups_with_contacts(const FetiSystem& system,
                                             const std::vector<UnheldGroup>& groups) {
  // No group (every plane scene): nothing to find, and G's copy by mode below is a
  // transposition of all of G (0.2 s at 1e7). Every process has the same groups.
  if (groups.empty()) return;
  const DualSpace& space = *space_;
  const Eigen::SparseMatrix<double, Eigen::RowMajor, int> by_mode = system.G();
  std::vector<double> sum(static_cast<size_t>(space.rows()), 0.0);
  std::vector<char> touched(static_cast<size_t>(space.rows()), 0);
  std::vector<SparseColumn> columns(groups.size()), directions(groups.size());
  std::vector<ExactSum> norms(groups.size());
  for (size_t i = 0; i < groups.size(); ++i) {
    if (i % kPollEvery == 0) throw_if_stopped("finding MPRGP's group constraints");
    std::vector<int> rows;
    for (Eigen::SparseVector<double>::InnerIterator z(groups[i].direction); z; ++z) {
      const int m = static_cast<int>(z.index());
      const double zm = z.value();
      if (zm == 0.0) continue;
      directions[i].index.push_back(m);
      directions[i].value.push_back(zm);
      for (Eigen::SparseMatrix<double, Eigen::RowMajor, int>::InnerIterator it(by_mode, m); it;
           ++it) {
        const auto r = static_cast<size_t>(it.col());
        if (!space.is_contact(it.col())) continue;
        if (!touched[r]) rows.push_back(it.col());
        touched[r] = 1;
        sum[r] += zm * it.value();
      }
    }
    std::sort(rows.begin(), rows.end());
    for (int r : rows) {
      const double value = sum[static_cast<size_t>(r)];
      sum[static_cast<size_t>(r)] = 0.0;
      touched[static_cast<size_t>(r)] = 0;
      if (value == 0.0) continue;
      columns[i].index.push_back(r);
      columns[i].value.push_back(value);
      if (space.owned(r)) norms[i].add(value * value);
    }
  }
  const std::vector<double> norm2 = values_of(norms, space.communicator());
  for (size_t i = 0; i < groups.size(); ++i) {
    if (!(norm2[i] > 0.0)) continue;  // no contact: boundedness decides
    columns_.push_back(std::move(columns[i]));
    directions_.push_back(std::move(directions[i]));
  }
}

// C'C: the diagonal and the pairs of groups that share a row (agreed by all processes),
// summed exactly; then one dense pseudo-inverse per block of linked groups.
void GroupBalance::factorize_blocks() {
  const DualSpace& space = *space_;
  const int k = size();
  if (k == 0) return;  // alike on every process (the groups' norms are summed over all)
  std::vector<std::vector<std::pair<int, double>>> on_row(static_cast<size_t>(space.rows()));
  for (int i = 0; i < k; ++i)
    for (size_t p = 0; p < columns_[i].index.size(); ++p)
      on_row[static_cast<size_t>(columns_[i].index[p])].emplace_back(i, columns_[i].value[p]);
  std::vector<int> local_pairs;
  for (const auto& groups : on_row)
    for (size_t a = 0; a < groups.size(); ++a)
      for (size_t b = a + 1; b < groups.size(); ++b) {
        local_pairs.push_back(groups[a].first);
        local_pairs.push_back(groups[b].first);
      }
  const std::vector<int> all = space.communicator().all_gather(local_pairs);
  std::vector<long long> keys;
  for (size_t p = 0; p + 1 < all.size(); p += 2)
    keys.push_back(static_cast<long long>(std::min(all[p], all[p + 1])) * k +
                   std::max(all[p], all[p + 1]));
  std::sort(keys.begin(), keys.end());
  keys.erase(std::unique(keys.begin(), keys.end()), keys.end());

  std::vector<ExactSum> sums(static_cast<size_t>(k) + keys.size());
  for (int r = 0; r < space.rows(); ++r) {
    if (!space.owned(r)) continue;
    const auto& groups = on_row[static_cast<size_t>(r)];
    for (size_t a = 0; a < groups.size(); ++a) {
      sums[static_cast<size_t>(groups[a].first)].add(groups[a].second * groups[a].second);
      for (size_t b = a + 1; b < groups.size(); ++b) {
        const long long key =
            static_cast<long long>(std::min(groups[a].first, groups[b].first)) * k +
            std::max(groups[a].first, groups[b].first);
        const auto at = std::lower_bound(keys.begin(), keys.end(), key) - keys.begin();
        sums[static_cast<size_t>(k) + static_cast<size_t>(at)].add(groups[a].second *
                                                                   groups[b].second);
      }
    }
  }
  const std::vector<double> entries = values_of(sums, space.communicator());

  scenes::UnionFind sets(k);
  for (long long key : keys)
    sets.join(static_cast<int>(key / k), static_cast<int>(key % k));
  int block_count = 0;
  const std::vector<int> block_of_group = sets.set_numbers(block_count);
  blocks_.resize(static_cast<size_t>(block_count));
  std::vector<int> position(static_cast<size_t>(k));
  for (int i = 0; i < k; ++i) {
    std::vector<int>& block = blocks_[static_cast<size_t>(block_of_group[i])].groups;
    position[static_cast<size_t>(i)] = static_cast<int>(block.size());
    block.push_back(i);
  }
  std::vector<Eigen::MatrixXd> grams(blocks_.size());
  for (size_t b = 0; b < blocks_.size(); ++b) {
    const int n = static_cast<int>(blocks_[b].groups.size());
    if (n > kMaxBlock)
      throw SolverError("MPRGP: " + std::to_string(n) +
                        " free motions of struts held only by contacts are linked through "
                        "shared contact rows, more than the " +
                        std::to_string(kMaxBlock) +
                        " it can balance together; use --method feti-c or active-set");
    grams[b].setZero(n, n);
  }
  const auto block_of = [&](int i) { return block_of_group[static_cast<size_t>(i)]; };
  for (int i = 0; i < k; ++i)
    grams[static_cast<size_t>(block_of(i))](position[i], position[i]) = entries[i];
  for (size_t p = 0; p < keys.size(); ++p) {
    const int i = static_cast<int>(keys[p] / k), j = static_cast<int>(keys[p] % k);
    Eigen::MatrixXd& gram = grams[static_cast<size_t>(block_of(i))];
    gram(position[i], position[j]) = gram(position[j], position[i]) = entries[k + p];
  }
  for (size_t b = 0; b < blocks_.size(); ++b) {
    if (b % kPollEvery == 0) throw_if_stopped("finding MPRGP's group constraints");
    blocks_[b].gram.compute(grams[b]);
  }
}

Eigen::VectorXd GroupBalance::transpose_times(const Eigen::VectorXd& x) const {
  std::vector<ExactSum> sums(columns_.size());
  for (size_t i = 0; i < columns_.size(); ++i)
    for (size_t p = 0; p < columns_[i].index.size(); ++p)
      if (space_->owned(columns_[i].index[p]))
        sums[i].add(columns_[i].value[p] * x(columns_[i].index[p]));
  const std::vector<double> values = values_of(sums, space_->communicator());
  return Eigen::Map<const Eigen::VectorXd>(values.data(), static_cast<Eigen::Index>(values.size()));
}

Eigen::VectorXd GroupBalance::times(const Eigen::VectorXd& a) const {
  Eigen::VectorXd out = Eigen::VectorXd::Zero(space_ ? space_->rows() : 0);
  for (size_t i = 0; i < columns_.size(); ++i)
    for (size_t p = 0; p < columns_[i].index.size(); ++p)
      out(columns_[i].index[p]) += a(static_cast<Eigen::Index>(i)) * columns_[i].value[p];
  return out;
}

Eigen::VectorXd GroupBalance::gram_solve(const Eigen::VectorXd& y) const {
  Eigen::VectorXd out = Eigen::VectorXd::Zero(size());
  for (const Block& block : blocks_) {
    const int n = static_cast<int>(block.groups.size());
    Eigen::VectorXd part(n);
    for (int p = 0; p < n; ++p)
      part(p) = y(block.groups[p]);
    const Eigen::VectorXd solved = block.gram.solve(part);
    for (int p = 0; p < n; ++p)
      out(block.groups[p]) = solved(p);
  }
  return out;
}

Eigen::VectorXd GroupBalance::direction_dots(const Eigen::VectorXd& e) const {
  Eigen::VectorXd out = Eigen::VectorXd::Zero(size());
  for (size_t i = 0; i < directions_.size(); ++i)
    for (size_t p = 0; p < directions_[i].index.size(); ++p)
      out(static_cast<Eigen::Index>(i)) += directions_[i].value[p] * e(directions_[i].index[p]);
  return out;
}

void GroupBalance::add_directions(const Eigen::VectorXd& a, Eigen::VectorXd& out) const {
  for (size_t i = 0; i < directions_.size(); ++i)
    for (size_t p = 0; p < directions_[i].index.size(); ++p)
      out(directions_[i].index[p]) += a(static_cast<Eigen::Index>(i)) * directions_[i].value[p];
}

}  // namespace fetic::solver
