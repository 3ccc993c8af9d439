#pragma once
// Which process owns which subdomains (MPI). The subdomains are ordered by a breadth-
// first walk over the graph in which two subdomains are neighbours when a row of B
// joins them (an interface of a strut, a contact), starting again at the lowest
// unvisited subdomain for every new group; the order is then cut into `parts`
// consecutive pieces of nearly equal unknowns. The pieces of a strut, and struts that
// touch, thus land on the same process where the balance allows, so most rows of B stay
// inside one process. The same on every process and independent of anything but the
// decomposition and the number of processes.

#include <vector>

#include "solver/decomposition.hpp"

namespace fetic::solver {

struct Partition {
  int parts = 1;
  std::vector<int> owner;                // per subdomain: its process
  std::vector<std::vector<int>> owned;   // per process: its subdomains, increasing

  int owner_of(int subdomain) const { return owner[subdomain]; }
  std::vector<int> subdomains_per_part() const;
  std::vector<long long> unknowns_per_part(const Decomposition& d) const;
};

Partition partition_subdomains(const Decomposition& decomposition, int parts);

}  // namespace fetic::solver
