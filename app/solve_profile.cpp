#include "app/solve_profile.hpp"

#include <sys/resource.h>

#include <cstdlib>

#include <nlohmann/json.hpp>

#include "app/output_file.hpp"
#include "solver/threads.hpp"

namespace fetic::app {
namespace {

// The numbers of one process, in a fixed order (a gather moves doubles).
std::vector<double> flatten(const ProfileRun& run) {
  const solver::ProcessProfile& a = run.before_solve;
  const solver::ProcessProfile& b = run.after_solve;
  const solver::CommunicationStats& ca = a.communication;
  const solver::CommunicationStats& cb = b.communication;
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return {static_cast<double>(b.subdomains),
          static_cast<double>(b.unknowns),
          static_cast<double>(b.rows),
          static_cast<double>(b.shared_rows),
          static_cast<double>(b.f_applications - a.f_applications),
          b.local_seconds - a.local_seconds,
          b.coarse_seconds - a.coarse_seconds,
          b.exchange_seconds - a.exchange_seconds,
          b.reduction_seconds - a.reduction_seconds,
          b.gather_seconds - a.gather_seconds,
          static_cast<double>(cb.exchanges - ca.exchanges),
          static_cast<double>(cb.messages - ca.messages),
          static_cast<double>(cb.bytes - ca.bytes),
          static_cast<double>(cb.reductions - ca.reductions),
          static_cast<double>(cb.gathers - ca.gathers),
          static_cast<double>(cb.gathered_bytes - ca.gathered_bytes),
          static_cast<double>(b.coarse_size),
          static_cast<double>(b.coarse_nonzeros),
          static_cast<double>(b.coarse_factorizations - a.coarse_factorizations),
          static_cast<double>(b.coarse_updates - a.coarse_updates),
          static_cast<double>(b.coarse_memory),
          static_cast<double>(b.factor_memory),
          static_cast<double>(usage.ru_maxrss) * 1024.0,
          b.coarse_seconds,
          b.memory.stiffness,
          b.memory.factor,
          b.memory.preconditioner_factor,
          b.memory.preconditioner_blocks,
          b.memory.incidence,
          b.memory.rigid_modes,
          b.memory.index,
          b.memory.workspaces,
          b.memory.loads,
          b.setup.decomposition,
          b.setup.incidence,
          b.setup.factorization,
          b.setup.coarse_space,
          b.preconditioner_setup_seconds,
          b.preconditioner_seconds - a.preconditioner_seconds,
          b.mode_product_seconds - a.mode_product_seconds,
          b.range_projection_seconds - a.range_projection_seconds,
          static_cast<double>(b.preconditioner_applications - a.preconditioner_applications),
          b.f_bytes_read,
          b.preconditioner_bytes_read,
          b.coarse_setup_seconds};
}

const char* const kFields[] = {"subdomains",
                               "unknowns",
                               "rows",
                               "shared_rows",
                               "f_applications",
                               "local_seconds",
                               "coarse_seconds",
                               "exchange_seconds",
                               "reduction_seconds",
                               "gather_seconds",
                               "exchanges",
                               "messages",
                               "bytes",
                               "reductions",
                               "gathers",
                               "gathered_bytes",
                               "coarse_size",
                               "coarse_nonzeros",
                               "coarse_factorizations",
                               "coarse_updates",
                               "coarse_memory_bytes",
                               "factor_memory_bytes",
                               "peak_resident_bytes",
                               "coarse_seconds_with_setup",
                               "stiffness_bytes",
                               "subdomain_factor_bytes",
                               "preconditioner_factor_bytes",
                               "preconditioner_block_bytes",
                               "incidence_bytes",
                               "rigid_mode_bytes",
                               "index_bytes",
                               "workspace_bytes",
                               "load_bytes",
                               "setup_decomposition_seconds",
                               "setup_incidence_seconds",
                               "setup_factorization_seconds",
                               "setup_coarse_space_seconds",
                               "setup_preconditioner_seconds",
                               "preconditioner_seconds",
                               "mode_product_seconds",
                               "range_projection_seconds",
                               "preconditioner_applications",
                               "f_bytes_read",
                               "preconditioner_bytes_read",
                               "setup_coarse_problem_seconds"};

}  // namespace

void write_solve_profile(const std::string& path, const solver::Communicator& processes,
                         const ProfileRun& run) {
  const std::vector<double> mine = flatten(run);
  const std::vector<double> all = processes.gather_to_root(mine);
  if (!processes.root()) return;
  nlohmann::json profile;
  profile["ranks"] = processes.size();
  profile["iterations"] = run.iterations;
  profile["setup_seconds"] = run.setup_seconds;
  profile["estimated_peak_bytes"] = run.estimated_peak_bytes;
  profile["solve_seconds"] = run.solve_seconds;
  // As the OpenMP runtime read it at start-up (fetic sets "passive" unless given: main.cpp).
  const char* wait_policy = std::getenv("OMP_WAIT_POLICY");
  profile["openmp_wait_policy"] = wait_policy ? wait_policy : "";
  // As glibc read them at start-up (fetic adds glibc.malloc.hugetlb=1 unless given: main.cpp).
  const char* tunables = std::getenv("GLIBC_TUNABLES");
  profile["glibc_tunables"] = tunables ? tunables : "";
  profile["threads"] = solver::thread_budget();
  if (run.mprgp_steps)
    profile["mprgp_steps"] = {{"conjugate_gradient", run.mprgp_steps->cg},
                              {"expansion", run.mprgp_steps->expansion},
                              {"proportioning", run.mprgp_steps->proportioning},
                              {"outer", run.mprgp_steps->outer}};
  if (run.mprgp_steps) {
    profile["setup_f_applications"] = run.setup_f_applications;
    profile["setup_norm_estimate_seconds"] = run.setup_norm_estimate_seconds;
  }
  if (run.contact_coarse_columns > 0)
    profile["contact_coarse_columns"] = run.contact_coarse_columns;
  if (run.condition.steps > 0)
    profile["condition_estimate"] = {{"cg_steps", run.condition.steps},
                                     {"lambda_min", run.condition.lambda_min},
                                     {"lambda_max", run.condition.lambda_max},
                                     {"kappa", run.condition.kappa()}};
  nlohmann::json list = nlohmann::json::array();
  const size_t fields = mine.size();
  for (int q = 0; q < processes.size(); ++q) {
    nlohmann::json entry;
    entry["rank"] = q;
    for (size_t f = 0; f < fields; ++f)
      entry[kFields[f]] = all[q * fields + f];
    list.push_back(entry);
  }
  profile["processes"] = list;
  write_output(path, [&](std::ostream& out) { out << profile.dump(1) << "\n"; });
}

}  // namespace fetic::app
