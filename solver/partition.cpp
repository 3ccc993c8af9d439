#include "solver/partition.hpp"

#include <algorithm>
#include <queue>

namespace fetic::solver {
namespace {

// Subdomains in breadth-first order over the rows of B that join two of them.
std::vector<int> breadth_first_order(const Decomposition& d) {
  const int count = static_cast<int>(d.subdomains.size());
  std::vector<std::vector<int>> neighbours(count);
  for (const Row& row : d.rows)
    for (size_t a = 0; a < row.entries.size(); ++a)
      for (size_t b = a + 1; b < row.entries.size(); ++b) {
        const int i = row.entries[a].subdomain, j = row.entries[b].subdomain;
        if (i == j) continue;
        neighbours[i].push_back(j);
        neighbours[j].push_back(i);
      }
  for (auto& list : neighbours) {
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
  }
  std::vector<int> order;
  order.reserve(count);
  std::vector<char> seen(count, 0);
  for (int start = 0; start < count; ++start) {
    if (seen[start]) continue;
    std::queue<int> queue;
    queue.push(start);
    seen[start] = 1;
    while (!queue.empty()) {
      const int s = queue.front();
      queue.pop();
      order.push_back(s);
      for (int n : neighbours[s])
        if (!seen[n]) {
          seen[n] = 1;
          queue.push(n);
        }
    }
  }
  return order;
}

}  // namespace

std::vector<int> Partition::subdomains_per_part() const {
  std::vector<int> counts;
  for (const auto& list : owned)
    counts.push_back(static_cast<int>(list.size()));
  return counts;
}

std::vector<long long> Partition::unknowns_per_part(const Decomposition& d) const {
  std::vector<long long> unknowns(parts, 0);
  for (size_t s = 0; s < owner.size(); ++s)
    unknowns[owner[s]] += d.subdomains[s].dof_count;
  return unknowns;
}

Partition partition_subdomains(const Decomposition& d, int parts) {
  Partition p;
  p.parts = std::max(1, parts);
  const int count = static_cast<int>(d.subdomains.size());
  p.owner.assign(count, 0);
  p.owned.assign(p.parts, {});
  if (p.parts > 1) {
    long long total = 0;
    for (const Subdomain& sub : d.subdomains)
      total += sub.dof_count;
    // Cut the order where the running total of unknowns crosses q/parts of the whole,
    // at the nearer subdomain boundary; every part gets at least one subdomain while
    // there are enough.
    long long running = 0;
    int part = 0;
    const std::vector<int> order = breadth_first_order(d);
    for (int i = 0; i < count; ++i) {
      const int s = order[i];
      const long long size = d.subdomains[s].dof_count;
      const int left = count - i;  // subdomains still to place, this one included
      const int parts_after = p.parts - 1 - part;
      const long long target = total * (part + 1) / p.parts;
      const bool cut = part < p.parts - 1 && running > 0 &&
                       (running + size / 2 > target || left <= parts_after);
      if (cut) ++part;
      p.owner[s] = part;
      running += size;
    }
  }
  for (int s = 0; s < count; ++s)
    p.owned[p.owner[s]].push_back(s);
  return p;
}

}  // namespace fetic::solver
