#include "solver/elimination_tree.hpp"

#include <numeric>

namespace fetic::solver {

void elimination_tree(const std::vector<int>& upper_start, const std::vector<int>& upper_rows,
                      int n, std::vector<int>& parent) {
  thread_local std::vector<int> ancestor;
  parent.assign(static_cast<std::size_t>(n), -1);
  ancestor.assign(static_cast<std::size_t>(n), -1);
  for (int k = 0; k < n; ++k)
    for (int e = upper_start[k]; e < upper_start[k + 1]; ++e)
      for (int i = upper_rows[e]; i != -1 && i < k;) {
        const int next = ancestor[i];
        ancestor[i] = k;
        if (next == -1) parent[i] = k;
        i = next;
      }
}

void postorder(const std::vector<int>& parent, std::vector<int>& post) {
  const int n = static_cast<int>(parent.size());
  thread_local std::vector<int> head, next, stack;
  head.assign(parent.size(), -1);
  next.resize(parent.size());
  for (int j = n - 1; j >= 0; --j)
    if (parent[j] != -1) {
      next[j] = head[parent[j]];
      head[parent[j]] = j;
    }
  post.clear();
  stack.clear();
  for (int root = 0; root < n; ++root) {
    if (parent[root] != -1) continue;
    stack.push_back(root);
    while (!stack.empty()) {
      const int top = stack.back(), child = head[top];
      if (child == -1) {
        stack.pop_back();
        post.push_back(top);
      } else {
        head[top] = next[child];
        stack.push_back(child);
      }
    }
  }
}

namespace {

// first[j]: the postorder index of the first node of j's subtree (its first descendant
// leaf). count[j] starts as 1 for a leaf, 0 otherwise (its diagonal: the row subtrees
// that start there).
void first_descendants(const std::vector<int>& parent, const std::vector<int>& post,
                       std::vector<int>& first, std::vector<int>& count) {
  const int n = static_cast<int>(parent.size());
  first.assign(parent.size(), -1);
  for (int k = 0; k < n; ++k) {
    int j = post[k];
    count[j] = first[j] == -1 ? 1 : 0;
    for (; j != -1 && first[j] == -1; j = parent[j])
      first[j] = k;
  }
}

// The root of the set holding `leaf` (the least common ancestor of the previous leaf and
// the current node), the path to it compressed.
int find_root(std::vector<int>& ancestor, int leaf) {
  int root = leaf;
  while (root != ancestor[root])
    root = ancestor[root];
  for (int s = leaf; s != root;) {
    const int up = ancestor[s];
    ancestor[s] = root;
    s = up;
  }
  return root;
}

}  // namespace

void column_counts(const std::vector<int>& lower_start, const std::vector<int>& lower_rows,
                   const std::vector<int>& parent, std::vector<int>& count, bool postordered) {
  const int n = static_cast<int>(parent.size());
  thread_local std::vector<int> post, first, max_first, previous_leaf, ancestor;
  if (postordered) {
    post.resize(parent.size());
    std::iota(post.begin(), post.end(), 0);
  } else {
    postorder(parent, post);
  }
  count.assign(parent.size(), 0);  // the differences, summed over subtrees at the end
  first_descendants(parent, post, first, count);
  max_first.assign(parent.size(), -1);
  previous_leaf.assign(parent.size(), -1);
  ancestor.resize(parent.size());
  std::iota(ancestor.begin(), ancestor.end(), 0);
  for (int k = 0; k < n; ++k) {
    const int j = post[k];
    if (parent[j] != -1) --count[parent[j]];
    // Rows i > j of column j: j is a leaf of row i's subtree when no node of j's subtree
    // was one before (first[j] beyond the largest first seen for row i).
    for (int e = lower_start[j]; e < lower_start[j + 1]; ++e) {
      const int i = lower_rows[e];
      if (i <= j || first[j] <= max_first[i]) continue;
      max_first[i] = first[j];
      const int previous = previous_leaf[i];
      previous_leaf[i] = j;
      ++count[j];
      if (previous != -1) --count[find_root(ancestor, previous)];  // the paths overlap there
    }
    if (parent[j] != -1) ancestor[j] = parent[j];
  }
  for (int j = 0; j < n; ++j)
    if (parent[j] != -1) count[parent[j]] += count[j];
  for (int j = 0; j < n; ++j)
    --count[j];  // the diagonal
}

}  // namespace fetic::solver
