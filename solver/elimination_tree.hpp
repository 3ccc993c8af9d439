#pragma once
// The symbolic pieces of a sparse Cholesky factorization L L' = C of a symmetric matrix C
// given as compressed columns (solver/supernodal_factorization.cpp): its elimination tree,
// a postorder of the tree, and the column counts of L. O(n) workspaces kept per thread.

#include <vector>

namespace fetic::solver {

// The elimination tree of C from its strict upper triangle's pattern (column k: rows i <
// k at upper_rows[upper_start[k] ..]), by Liu's algorithm with path compression:
// parent[j] = -1 for a root.
void elimination_tree(const std::vector<int>& upper_start, const std::vector<int>& upper_rows,
                      int n, std::vector<int>& parent);

// A postorder of the forest `parent` (children in increasing order, by depth-first search):
// post[k] is the node visited k-th. Each subtree's nodes become consecutive, so chains of
// the tree become runs of columns (supernodes).
void postorder(const std::vector<int>& parent, std::vector<int>& post);

// The entries below the diagonal of each column of L, from C's lower triangle (column j:
// rows i >= j at lower_rows[lower_start[j] ..]) and its elimination tree, by Gilbert, Ng
// and Peyton's algorithm (as CSparse's cs_counts): each row subtree's leaves and their
// least common ancestors, O(nnz(C)) near enough, instead of walking every row subtree
// (O(nnz(L)), a tenth of a subdomain's factorization). `postordered`: the columns are in a
// postorder of the tree already (no postorder is computed).
void column_counts(const std::vector<int>& lower_start, const std::vector<int>& lower_rows,
                   const std::vector<int>& parent, std::vector<int>& count,
                   bool postordered = false);

}  // namespace fetic::solver
