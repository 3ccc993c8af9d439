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
  // Per element the number of its set, the sets numbered 0, 1, ... in the order of their
  // first elements; `count` receives how many sets there are.
  std::vector<int> set_numbers(int& count) {
    const int n = static_cast<int>(parent_.size());
    std::vector<int> number_of_root(parent_.size(), -1), numbers(parent_.size());
    count = 0;
    for (int i = 0; i < n; ++i) {
      int& number = number_of_root[static_cast<size_t>(root(i))];
      if (number < 0) number = count++;
      numbers[static_cast<size_t>(i)] = number;
    }
    return numbers;
  }

 private:
  std::vector<int> parent_;
};

}  // namespace fetic::scenes
