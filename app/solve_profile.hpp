#pragma once
// `fetic solve --profile FILE`: what each process did during the solve phase (after
// set-up) - time in local solves, neighbour exchanges, reductions, gathers and the coarse
// problem; messages, bytes and reductions; the coarse problem's size; factor memory and
// peak resident memory - gathered on rank 0 and written as JSON; for MPRGP also how its
// iterations split into step kinds. The distributed benchmark (bench/mpi_scaling.py)
// reads it.

#include <optional>
#include <string>

#include "solver/feti_method.hpp"
#include "solver/mprgp.hpp"

namespace fetic::app {

struct ProfileRun {
  solver::ProcessProfile before_solve;  // reading after set-up
  solver::ProcessProfile after_solve;
  double setup_seconds = 0.0;
  double solve_seconds = 0.0;
  int iterations = 0;
  double estimated_peak_bytes = 0.0;  // the memory check's estimate (memory_estimate.hpp)
  // MPRGP's steps in the last solve (the same on every process).
  std::optional<solver::Mprgp::Counts> mprgp_steps;
  // Lanczos estimate of the preconditioned dual operator's condition (the last solve).
  solver::ConditionEstimate condition;
  // MPRGP's set-up: applications of F (the Lanczos estimate of ||F||, FETI-DP's contact
  // coarse space) and the columns of FETI-DP's coarse space of the contact faces.
  int setup_f_applications = 0;
  double setup_norm_estimate_seconds = 0.0;  // MPRGP's Lanczos estimate of ||H||
  int contact_coarse_columns = 0;
};

// Collective. Rank 0 writes `path` (throws OutputError when it cannot).
void write_solve_profile(const std::string& path, const solver::Communicator& processes,
                         const ProfileRun& run);

}  // namespace fetic::app
