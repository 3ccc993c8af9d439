#include "app/memory_estimate.hpp"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <thread>

namespace fetic::app {
namespace {

// Measured on generated scenes (fetic generate; peak resident memory of `fetic solve`,
// /usr/bin/time -f %M; docs/RELIABILITY.md, "Memory"): bytes per item, least squares
// weighted by 1/peak (relative error) over bar, plane and frame scenes of 1e4 to 1e6
// unknowns, then raised by 5% so that the estimate errs on the side of room.
constexpr double kBase = 13.5e6;  // the program itself (and its libraries: MPI, CHOLMOD, GL)
constexpr double kMargin = 1.05;
// The dual methods: per subdomain a factor of K_j (FETI-DP: of its remainder K_rr) and,
// with the Dirichlet preconditioner, one of its interior K_ii, each kept as its nonzeros
// only (solver/compact_factor.hpp); B's rows and their index arrays; the coarse problem;
// dual vectors. Per strut: its mesh, element data and results. The lumped preconditioner
// keeps every K_j (about as many entries as unknowns times DOFs per node).
struct DualCosts {
  double per_unknown, per_strut, per_interface_row, per_factor_entry, per_single_factor_entry,
      per_interior_factor_entry, per_kept_stiffness_entry;
};
// Fitted 5 December 2026 on 35-40 runs each (docs/RELIABILITY.md lists them). FETI-DP's
// factor entries are those of K_j's estimate (K_rr has a few fewer); its interior factors
// fold into them (the fit found no separate share); single precision keeps 83% of an
// entry there against 60% for FETI-C's (its corner problem stays double).
// The factor entries' costs were scaled on 5 December (afternoon) by the supernodal compact
// factors' bytes against the column-by-column ones on a plane scene (K_j's factor 0.85,
// the interior's and single precision 0.75-0.8: one row index per supernode, not per entry).
constexpr DualCosts kFetiCCosts{98, 49900, 1260, 6.1, 3.5, 2.6, 33};
constexpr DualCosts kMprgpCosts{103, 45700, 1710, 5.7, 3.2, 2.85, 34};
constexpr DualCosts kFetiDpCosts{156, 6500, 220, 14.7, 12.3, 0.0, 0.0};
// FETI-C's and MPRGP's interior factors: in single precision since 5 December
// (SolveOptions::single_interior_factors; the costs above were fitted with them double),
// 0.6 of the fitted cost; since 6 December one factor per subdomain with the boundary
// last (solver/boundary_last.hpp) instead of K_j's and K_ii's: its entries beyond K_j's
// are double, and K_bb and K_ib are no longer held - the peak of the 984,900-unknown
// scene grew by 30 MB, 0.75 of the fitted cost of fill(K_ii) (docs/BENCHMARKS.md, "One
// subdomain factor with the boundary last").
constexpr double kInteriorFactorShare = 0.75;
// Active set: K factorized per strut, the contact rows solved against it (dense, per
// strut), the working-set system (dense, up to every pair: twice, for the LU).
constexpr double kActivePerUnknown = 320, kActivePerStrut = 3300, kActivePerFactorEntry = 5,
                 kActivePerContactColumn = 23, kActivePerPairSquared = 16;
// CG and SD: K and a few vectors.
constexpr double kGradientPerUnknown = 600, kGradientPerStrut = 3300;
// The result file is written streamed (app/json_stream.hpp) and the ParaView files are
// made a strut at a time (app/vtu_export.hpp; one array's compressed blocks are held):
// together they add about 18 bytes a node and 0.4 MB to a solve's peak (fitted with the
// dual methods' costs; docs/RELIABILITY.md, "Memory").
constexpr double kResultFilePerNode = 10, kResultFileFixed = 0.2e6;
constexpr double kParaViewPerNode = 8, kParaViewFixed = 0.2e6;
// A snapshot: the displacement pieces and the dual or primal iterate.
constexpr double kIteratePerUnknown = 24, kIteratePerRow = 16;
// toml++'s tree and the text, per byte of the file.
constexpr double kParsePerByte = 16;

// Entries of a CHOLMOD factor per DOF for a grid of a x b nodes with `per_node` DOFs:
// a chain (b = 1) is banded; a grid fills like its narrower side until nested dissection
// (log of its size) is cheaper. Bounds measured factors from above by up to 1.6x
// (e.g. 32x8 elements: 22.5 measured, 27 estimated; 128x128: 98 and 105).
double fill_per_dof(double a, double b, double per_node) {
  if (std::min(a, b) <= 1.0) return 2.0 * per_node;
  const double dofs = per_node * a * b;
  return std::min(3.0 * std::min(a, b), 7.0 * std::log2(dofs)) * per_node / 2.0;
}

struct Counts {
  double unknowns = 0, struts = 0, interface_rows = 0, pairs = 0;
  double subdomain_fill = 0, interior_fill = 0, strut_fill = 0, contact_columns = 0, nodes = 0;
};

Counts count(const scenes::Scene& scene) {
  Counts c;
  double nodes = 0;
  for (const scenes::Strut& s : scene.struts)
    nodes += (s.elements + 1.0) * scenes::nodes_across(scene, s);
  c.unknowns = static_cast<double>(scenes::unknowns(scene));
  c.nodes = nodes;
  const double per_node = nodes > 0 ? c.unknowns / nodes : 1.0;
  // Contact rows per strut: every pair of a contact of that strut.
  std::vector<double> rows(scene.struts.size(), 0.0);
  for (const scenes::Contact& contact : scene.contacts) {
    const double pairs = scenes::nodes_across(scene, scene.struts.at(contact.a.strut));
    c.pairs += pairs;
    rows.at(contact.a.strut) += pairs;
    rows.at(contact.b.strut) += pairs;
  }
  for (size_t i = 0; i < scene.struts.size(); ++i) {
    const scenes::Strut& s = scene.struts[i];
    const double along = s.elements + 1.0, across = scenes::nodes_across(scene, s);
    const double sx = std::max(1, s.subdomains);
    const double sy = across > 1 ? std::max(1, s.subdomains_across) : 1.0;
    const double dofs = along * across * per_node;
    c.struts += 1;
    const double box_along = std::ceil(s.elements / sx) + 1.0;
    const double box_across = across > 1 ? std::ceil(s.elements_across / sy) + 1.0 : 1.0;
    // K_j's factor and its interior's (the box less its outer ring of nodes).
    const double inner_along = std::max(1.0, box_along - 2.0);
    const double inner_across = across > 1 ? std::max(1.0, box_across - 2.0) : 1.0;
    c.subdomain_fill +=
        sx * sy * box_along * box_across * per_node * fill_per_dof(box_along, box_across, per_node);
    c.interior_fill += sx * sy * inner_along * inner_across * per_node *
                       fill_per_dof(inner_along, inner_across, per_node);
    c.strut_fill += dofs * fill_per_dof(along, across, per_node);
    c.interface_rows += ((sx - 1) * across + (sy - 1) * along) * per_node +
                        ((s.fixed_from ? 1 : 0) + (s.fixed_to ? 1 : 0)) * across * per_node;
    c.contact_columns += dofs * rows[i];
  }
  c.interface_rows += c.pairs;
  return c;
}

double dual_bytes(const Counts& c, const DualCosts& k, const MemoryUse& use) {
  const double per_entry = use.single_factors ? k.per_single_factor_entry : k.per_factor_entry;
  const double interior = use.dirichlet ? k.per_interior_factor_entry * kInteriorFactorShare : 0.0;
  const double dofs_per_node = c.nodes > 0 ? c.unknowns / c.nodes : 1.0;
  const double kept_stiffness = use.dirichlet ? 0.0 : c.unknowns * dofs_per_node;
  return kMargin * (kBase + k.per_unknown * c.unknowns + k.per_strut * c.struts +
                    k.per_interface_row * c.interface_rows + per_entry * c.subdomain_fill +
                    interior * c.interior_fill + k.per_kept_stiffness_entry * kept_stiffness);
}

double method_bytes(const Counts& c, solver::MethodKind method, const MemoryUse& use) {
  switch (method) {
    case solver::MethodKind::Feti:
    case solver::MethodKind::FetiC:
      return dual_bytes(c, kFetiCCosts, use);
    case solver::MethodKind::Mprgp:
      return dual_bytes(c, kMprgpCosts, use);
    case solver::MethodKind::FetiDp:
      return dual_bytes(c, kFetiDpCosts, use);
    case solver::MethodKind::ActiveSet:
      return kBase + kActivePerUnknown * c.unknowns + kActivePerStrut * c.struts +
             kActivePerFactorEntry * c.strut_fill + kActivePerContactColumn * c.contact_columns +
             kActivePerPairSquared * c.pairs * c.pairs;
    case solver::MethodKind::ConjugateGradient:
    case solver::MethodKind::SteepestDescent:
      return kBase + kGradientPerUnknown * c.unknowns + kGradientPerStrut * c.struts;
  }
  return kBase;
}

std::optional<double> read_number(const std::string& path) {
  std::ifstream in(path);
  std::string text;
  if (!(in >> text) || text == "max") return std::nullopt;
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  if (end == text.c_str()) return std::nullopt;
  return value;
}

// Memory the cgroup (v2, or v1's memory controller) still allows: the tightest of the
// limits less the usage from the process's cgroup up to the root.
std::optional<double> cgroup_room() {
  std::ifstream in("/proc/self/cgroup");
  std::optional<double> room;
  for (std::string line; std::getline(in, line);) {
    const size_t first = line.find(':'), second = line.find(':', first + 1);
    if (first == std::string::npos || second == std::string::npos) continue;
    const std::string controllers = line.substr(first + 1, second - first - 1);
    std::string path = line.substr(second + 1);
    const bool v2 = controllers.empty();
    const bool v1 = controllers.find("memory") != std::string::npos;
    if (!v2 && !v1) continue;
    const std::string root = v2 ? "/sys/fs/cgroup" : "/sys/fs/cgroup/memory";
    while (true) {
      const std::string dir = root + (path == "/" ? "" : path);
      const auto limit = read_number(dir + (v2 ? "/memory.max" : "/memory.limit_in_bytes"));
      const auto usage = read_number(dir + (v2 ? "/memory.current" : "/memory.usage_in_bytes"));
      if (limit && usage && *limit < 1e18) {
        const double left = std::max(0.0, *limit - *usage);
        room = room ? std::min(*room, left) : left;
      }
      if (path.empty() || path == "/") break;
      path = path.substr(0, path.rfind('/'));
      if (path.empty()) path = "/";
    }
  }
  return room;
}

// Pages of the process: total address space and data segment (/proc/self/statm).
std::pair<double, double> address_space_and_data() {
  std::ifstream in("/proc/self/statm");
  double size = 0, resident = 0, shared = 0, text = 0, lib = 0, data = 0;
  in >> size >> resident >> shared >> text >> lib >> data;
  const double page = static_cast<double>(::sysconf(_SC_PAGESIZE));
  return {size * page, data * page};
}

}  // namespace

MemoryEstimate estimate_memory(const scenes::Scene& scene, const MemoryUse& use) {
  const Counts c = count(scene);
  MemoryEstimate estimate;
  for (const solver::MethodKind method : use.methods) {
    const double bytes = method_bytes(c, method, use);
    if (bytes > estimate.bytes) {
      estimate.bytes = bytes;
      estimate.largest = solver::to_string(method);
    }
  }
  if (use.result_file) estimate.bytes += kResultFileFixed + kResultFilePerNode * c.nodes;
  if (use.paraview) estimate.bytes += kParaViewFixed + kParaViewPerNode * c.nodes;
  const double iterate = kIteratePerUnknown * c.unknowns + kIteratePerRow * c.interface_rows;
  double kept = use.kept_iterates * iterate;
  if (use.kept_iterate_budget > 0.0)  // the window's store thins to its budget, keeping 3
    kept = std::min(kept, std::max(use.kept_iterate_budget, 3.0 * iterate));
  estimate.bytes += kept;
  return estimate;
}

double estimate_parse_memory(double bytes) {
  return kBase + kParsePerByte * bytes;
}

std::optional<AvailableMemory> available_memory() {
  std::optional<AvailableMemory> best;
  const auto consider = [&](double bytes, const char* what) {
    if (!best || bytes < best->bytes) best = AvailableMemory{std::max(0.0, bytes), what};
  };
  {
    std::ifstream in("/proc/meminfo");
    for (std::string key; in >> key;) {
      double kb = 0;
      std::string unit;
      in >> kb >> unit;
      if (key == "MemAvailable:") {
        consider(kb * 1024, "the machine's available memory (MemAvailable)");
        break;
      }
    }
  }
  if (const auto room = cgroup_room()) consider(*room, "the cgroup's memory limit");
  const auto [space, data] = address_space_and_data();
  rlimit limit{};
  // Address space beyond the memory used: thread stacks and glibc's malloc arenas of the
  // worker threads, and the allocator's slack. Measured: a FETI-C solve of 492 MB resident
  // needs 520-560 MB of RLIMIT_AS on 2 threads; kept: 64 MB and 32 MB per core.
  const double reserve =
      64e6 + 32e6 * std::clamp(static_cast<double>(std::thread::hardware_concurrency()), 1.0, 16.0);
  if (::getrlimit(RLIMIT_AS, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY)
    consider(static_cast<double>(limit.rlim_cur) - space - reserve,
             "the address-space limit (ulimit -v)");
  if (::getrlimit(RLIMIT_DATA, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY)
    consider(static_cast<double>(limit.rlim_cur) - data - reserve,
             "the data-segment limit (ulimit -d)");
  return best;
}

std::string memory_text(double bytes) {
  char text[32];
  if (bytes >= 1e9)
    std::snprintf(text, sizeof text, "%.1f GB", bytes / 1e9);
  else
    std::snprintf(text, sizeof text, "%.0f MB", std::ceil(bytes / 1e6));
  return text;
}

bool memory_check_enabled() {
  const char* setting = std::getenv("FETIC_MEMORY_CHECK");
  return !setting || std::string(setting) != "off";
}

}  // namespace fetic::app
