#include "solver/contact_batches.hpp"

#include <algorithm>

#include "scenes/union_find.hpp"

namespace fetic::solver {
namespace {

// Joins the subdomains of every equality row, and of every contact row between subdomains
// that all have rigid-body modes (see the header); numbers the blocks 0, 1, ...
std::vector<int> join_subdomains(const Decomposition& d, int& block_count) {
  const int n = static_cast<int>(d.subdomains.size());
  scenes::UnionFind joined(n);
  for (int r = 0; r < d.row_count(); ++r) {
    const std::vector<RowEntry>& entries = d.rows[r].entries;
    if (entries.size() < 2) continue;
    bool join = r < d.equality_rows;
    if (!join) {
      join = true;
      for (const RowEntry& e : entries)
        join = join && d.subdomains[e.subdomain].mode_count > 0;
    }
    if (!join) continue;
    for (const RowEntry& e : entries)
      joined.join(entries.front().subdomain, e.subdomain);
  }
  return joined.set_numbers(block_count);
}

// Per block, the other blocks a row joins it to.
std::vector<std::vector<int>> neighbours(const Decomposition& d, const std::vector<int>& block,
                                         int block_count) {
  std::vector<std::vector<int>> out(block_count);
  for (const Row& row : d.rows)
    for (const RowEntry& a : row.entries)
      for (const RowEntry& b : row.entries)
        if (block[a.subdomain] != block[b.subdomain])
          out[block[a.subdomain]].push_back(block[b.subdomain]);
  for (std::vector<int>& list : out) {
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
  }
  return out;
}

// Greedy colouring in column order: a column takes the first batch with no column whose
// blocks equal or neighbour its own.
std::vector<std::vector<int>> colour(const std::vector<std::vector<int>>& column_blocks,
                                     const std::vector<std::vector<int>>& next_to,
                                     int block_count) {
  std::vector<std::vector<int>> batches;
  std::vector<std::vector<int>> batches_at(block_count);  // batches of the columns on a block
  std::vector<int> taken;                                 // per batch: last column it conflicted
  const int columns = static_cast<int>(column_blocks.size());
  for (int c = 0; c < columns; ++c) {
    const auto mark = [&](int b) {
      for (int k : batches_at[b])
        taken[k] = c;
    };
    for (int b : column_blocks[c]) {
      mark(b);
      for (int n : next_to[b])
        mark(n);
    }
    int k = 0;
    while (k < static_cast<int>(batches.size()) && taken[k] == c)
      ++k;
    if (k == static_cast<int>(batches.size())) {
      batches.emplace_back();
      taken.push_back(-1);
    }
    batches[k].push_back(c);
    for (int b : column_blocks[c])
      batches_at[b].push_back(k);
  }
  return batches;
}

// The columns linked by shared blocks, each component increasing, in order of its first.
std::vector<std::vector<int>> components(const std::vector<std::vector<int>>& column_blocks,
                                         int block_count) {
  const int columns = static_cast<int>(column_blocks.size());
  scenes::UnionFind linked(columns);
  std::vector<int> first_on(block_count, -1);
  for (int c = 0; c < columns; ++c)
    for (int b : column_blocks[c]) {
      if (first_on[b] < 0) first_on[b] = c;
      linked.join(first_on[b], c);
    }
  int count = 0;
  const std::vector<int> number = linked.set_numbers(count);
  std::vector<std::vector<int>> out(count);
  for (int c = 0; c < columns; ++c)
    out[number[c]].push_back(c);
  return out;
}

}  // namespace

ContactBatches batch_columns(const Decomposition& d,
                             const std::vector<std::vector<int>>& column_rows) {
  ContactBatches out;
  out.block_of_subdomain = join_subdomains(d, out.block_count);
  for (const std::vector<int>& rows : column_rows) {
    std::vector<int> blocks;
    for (int r : rows)
      for (const RowEntry& e : d.rows[r].entries)
        blocks.push_back(out.block_of_subdomain[e.subdomain]);
    std::sort(blocks.begin(), blocks.end());
    blocks.erase(std::unique(blocks.begin(), blocks.end()), blocks.end());
    out.column_blocks.push_back(std::move(blocks));
  }
  out.batches = colour(out.column_blocks, neighbours(d, out.block_of_subdomain, out.block_count),
                       out.block_count);
  out.components = components(out.column_blocks, out.block_count);
  return out;
}

}  // namespace fetic::solver
