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
// /usr/bin/time -f %M; docs/RELIABILITY.md): bytes per item, least squares.
constexpr double kBase = 18e6;  // the program itself (and its libraries: MPI, CHOLMOD, GL)
// FETI and FETI-C: per subdomain a factor of K_j and one of its interior K_ii (the
// Dirichlet preconditioner's), each freely ordered and kept as its nonzeros only
// (solver/compact_factor.hpp), B's rows, the coarse problem, dual vectors. The factor's
// cost per estimated entry was refitted for them (docs/BENCHMARKS.md, "Lean factors"):
// 5.2 bytes on 20x24-element subdomains (the fill estimate is about twice the true fill).
// Per unknown 200 bytes less since K_j's storage is really freed (solver/feti_system.cpp:
// an Eigen matrix assigned an empty one kept its arrays; 1,014 -> 819 MB at 984,900).
// Single precision factors (--single-factors) keep 6 of the 10 bytes an entry.
constexpr double kFetiPerUnknown = 180, kFetiPerStrut = 4500, kFetiPerSubdomain = 5000,
                 kFetiPerFactorEntry = 5.2, kFetiPerInterfaceRow = 2500, kSingleFactorShare = 0.6;
// Active set: K factorized per strut, the contact rows solved against it (dense, per
// strut), the working-set system (dense, up to every pair: twice, for the LU).
constexpr double kActivePerUnknown = 320, kActivePerStrut = 3300, kActivePerFactorEntry = 5,
                 kActivePerContactColumn = 23, kActivePerPairSquared = 16;
// MPRGP: FETI-C's, plus its face projector: a second sparse coarse factor (the dense
// correction over the modes next to contacts it once held is gone: face_projector.hpp).
constexpr double kModesPerSubdomain = 3, kFaceProjectorPerMode = 2000;
// CG and SD: K and a few vectors.
constexpr double kGradientPerUnknown = 600, kGradientPerStrut = 3300;
// The result file is written streamed (app/json_stream.hpp) and the ParaView files are
// made a strut at a time (app/vtu_export.hpp; one array's compressed blocks are held):
// together they added 17 MB to the 984,900-unknown solve's peak and 43 MB to the
// 2.9e6-unknown one's (about 30 bytes a node; docs/RELIABILITY.md, "Memory").
constexpr double kResultFilePerNode = 20;
constexpr double kParaViewPerNode = 10;
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
  double unknowns = 0, struts = 0, subdomains = 0, interface_rows = 0, pairs = 0;
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
    c.subdomains += sx * sy;
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

double method_bytes(const Counts& c, solver::MethodKind method, const MemoryUse& use) {
  const double per_entry = kFetiPerFactorEntry * (use.single_factors ? kSingleFactorShare : 1.0);
  // The interior factors are the Dirichlet preconditioner's only.
  const double fill = c.subdomain_fill + (use.dirichlet ? c.interior_fill : 0.0);
  switch (method) {
    case solver::MethodKind::Feti:
    case solver::MethodKind::FetiC:
      return kBase + kFetiPerUnknown * c.unknowns + kFetiPerStrut * c.struts +
             kFetiPerSubdomain * c.subdomains + per_entry * fill +
             kFetiPerInterfaceRow * c.interface_rows;
    case solver::MethodKind::Mprgp:
    case solver::MethodKind::FetiDp:
      return method_bytes(c, solver::MethodKind::FetiC, use) +
             kFaceProjectorPerMode * kModesPerSubdomain * c.subdomains;
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
  if (use.result_file) estimate.bytes += kResultFilePerNode * c.nodes;
  if (use.paraview) estimate.bytes += kParaViewPerNode * c.nodes;
  estimate.bytes +=
      use.kept_iterates * (kIteratePerUnknown * c.unknowns + kIteratePerRow * c.interface_rows);
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
