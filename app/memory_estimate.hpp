#pragma once
// How much memory a command will need for a scene, estimated before anything is built,
// and how much the process may still take - so that a scene too large for the machine is
// refused with the figures at once instead of ending in std::bad_alloc after minutes.
//
// The estimate counts what the scene has (unknowns, struts, subdomains, interface rows,
// contact pairs) and the fill of the CHOLMOD factors (estimated per subdomain or strut
// from its node grid), each with a cost per item measured as peak resident memory on
// generated scenes (docs/RELIABILITY.md, "Memory"; within 10% for FETI-C, within 50%
// for the active-set method).

#include <optional>
#include <string>
#include <vector>

#include "scenes/scene.hpp"
#include "solver/method.hpp"

namespace fetic::app {

// What a command will do with the scene.
struct MemoryUse {
  std::vector<solver::MethodKind> methods;  // run one after another: the largest counts
  bool result_file = false;                 // the result JSON of every node
  int kept_iterates = 0;                    // snapshots held at once (the gui keeps a solve's)
  bool paraview = false;                    // --vtu: ParaView files of every node
  bool single_factors = false;              // --single-factors: 6 bytes a factor entry, not 10
  bool dirichlet = true;                    // the Dirichlet preconditioner's K_ii factors
  double kept_iterate_budget = 0.0;         // > 0: those snapshots' bytes at most this (but 3)
};

struct MemoryEstimate {
  double bytes = 0.0;
  std::string largest;  // what needs the most, e.g. "feti-c"
};

MemoryEstimate estimate_memory(const scenes::Scene& scene, const MemoryUse& use);

// Peak memory of parsing a scene file of `bytes` (toml++'s tree: about 16 times the text).
double estimate_parse_memory(double bytes);

// What this process may still allocate: the smallest of the kernel's MemAvailable, the
// cgroup's memory.max less its usage (v2, or v1's limit), RLIMIT_AS less the address
// space in use and RLIMIT_DATA less the data segment. `limited_by` names the smallest.
struct AvailableMemory {
  double bytes = 0.0;
  std::string limited_by;
};
std::optional<AvailableMemory> available_memory();

// "1.4 GB", "320 MB".
std::string memory_text(double bytes);

// FETIC_MEMORY_CHECK=off skips the refusal (the estimate errs on the large side for some
// shapes); std::bad_alloc is then still reported as "out of memory while ..." (status 7).
bool memory_check_enabled();

}  // namespace fetic::app
