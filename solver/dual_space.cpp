#include "solver/dual_space.hpp"

#include <algorithm>
#include <cmath>
#include <map>

namespace fetic::solver {

DualSpace::DualSpace(const Decomposition& decomposition)
    : communicator_(&Communicator::self()), first_contact_(decomposition.equality_rows) {
  const int rows = decomposition.row_count();
  kind_.reserve(rows);
  global_.resize(rows);
  local_.resize(rows);
  for (int r = 0; r < rows; ++r) {
    kind_.push_back(decomposition.rows[r].kind);
    global_[r] = r;
    local_[r] = r;
  }
}

DualSpace::DualSpace(const Decomposition& d, const Partition& partition,
                     const Communicator& communicator)
    : communicator_(&communicator) {
  const int me = communicator.rank();
  const int rows = d.row_count();
  local_.assign(rows, -1);
  owned_.clear();
  std::map<int, Peer> peers;
  first_contact_ = -1;
  for (int r = 0; r < rows; ++r) {
    const Row& row = d.rows[r];
    int lowest = -1;
    bool mine = false;
    for (const RowEntry& entry : row.entries) {
      if (lowest < 0 || entry.subdomain < lowest) lowest = entry.subdomain;
      mine = mine || partition.owner_of(entry.subdomain) == me;
    }
    if (!mine) continue;
    const int local = static_cast<int>(global_.size());
    if (row.kind == RowKind::Contact && first_contact_ < 0) first_contact_ = local;
    local_[r] = local;
    global_.push_back(r);
    kind_.push_back(row.kind);
    owned_.push_back(partition.owner_of(lowest) == me ? 1 : 0);
    std::vector<int> others;
    for (const RowEntry& entry : row.entries) {
      const int q = partition.owner_of(entry.subdomain);
      if (q != me) others.push_back(q);
    }
    std::sort(others.begin(), others.end());
    others.erase(std::unique(others.begin(), others.end()), others.end());
    for (int q : others) {
      peers[q].rank = q;
      peers[q].rows.push_back(local);
    }
  }
  if (first_contact_ < 0) first_contact_ = static_cast<int>(global_.size());
  for (auto& [q, peer] : peers) {
    exchange_peers_.push_back({q, static_cast<int>(peer.rows.size())});
    peers_.push_back(std::move(peer));
  }
  int total = 0;
  for (const Peer& peer : peers_)
    total += static_cast<int>(peer.rows.size());
  send_.resize(total);
  receive_.resize(total);
}

double DualSpace::dot(const Eigen::VectorXd& a, const Eigen::VectorXd& b) const {
  ExactSum sum = owned_.empty() ? exact_dot(a.data(), b.data(), a.size())
                                : exact_dot(a.data(), b.data(), a.size(), owned_.data());
  communicator_->sum(&sum, 1);
  return sum.value();
}

double DualSpace::norm(const Eigen::VectorXd& a) const {
  return std::sqrt(dot(a, a));
}

double DualSpace::max_abs(const Eigen::VectorXd& a) const {
  return max(a.size() > 0 ? a.lpNorm<Eigen::Infinity>() : 0.0);
}

void DualSpace::exchange_shared_rows(const Eigen::VectorXd& values) const {
  int offset = 0;
  for (const Peer& peer : peers_)
    for (int r : peer.rows)
      send_[offset++] = values(r);
  communicator_->exchange(exchange_peers_, send_, receive_);
}

void DualSpace::complete_rows(Eigen::VectorXd& partial) const {
  if (peers_.empty()) return;
  exchange_shared_rows(partial);
  // Add the partials in rank order, so every process holding the row gets the same bits.
  // A row joins at most two subdomains, hence at most one peer per row: mine + theirs in
  // rank order (which for two terms is also the order-free IEEE sum).
  int offset = 0;
  const int me = communicator_->rank();
  for (const Peer& peer : peers_)
    for (int r : peer.rows) {
      const double theirs = receive_[offset++];
      partial(r) = peer.rank < me ? theirs + partial(r) : partial(r) + theirs;
    }
}

Eigen::VectorXd DualSpace::other_side(const Eigen::VectorXd& mine) const {
  Eigen::VectorXd theirs = Eigen::VectorXd::Zero(rows());
  if (peers_.empty()) return theirs;
  exchange_shared_rows(mine);
  int offset = 0;
  for (const Peer& peer : peers_)
    for (int r : peer.rows)
      theirs(r) = receive_[offset++];
  return theirs;
}

}  // namespace fetic::solver
