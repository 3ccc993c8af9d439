#pragma once
// Disjoint sets over 0..n-1 (path halving): the groups a relation joins - struts joined
// by joints, working-set rows that share a subdomain, motions a contact couples.

#include <numeric>
#include <vector>

namespace fetic::scenes {

class UnionFind {
 public:
  explicit UnionFind(int n) : parent_(static_cast<size_t>(n)) {
    std::iota(parent_.begin(), parent_.end(), 0);
  }
  // The representative of i's set.
  int root(int i) {
    while (parent_[static_cast<size_t>(i)] != i)
      i = parent_[static_cast<size_t>(i)] =
          parent_[static_cast<size_t>(parent_[static_cast<size_t>(i)])];
    return i;
  }
  // Puts a's set into b's.
  void join(int a, int b) { parent_[static_cast<size_t>(root(a))] = root(b); }

 private:
  std::vector<int> parent_;
};

}  // namespace fetic::scenes
