#include "solver/pcpg.hpp"

namespace fetic::solver {
namespace {

const Model& refuse_contacts(const Model& model) {
  if (!model.pairs.empty())
    throw SolverError("FETI-1 (--method feti) solves scenes without contacts; this scene has " +
                      std::to_string(model.contact_labels.size()) +
                      " contact(s): use --method feti-c");
  return model;
}

}  // namespace

Pcpg::Pcpg(const Model& model, const SolveOptions& options, const Communicator& communicator)
    : FetiMethod(kind_of(MethodKind::Feti, options), refuse_contacts(model), options, 0,
                 communicator) {
  if (options.max_iterations <= 0) max_iterations_ = 10 * system_.space().global_rows() + 100;
  coarse_.set_active_rows(std::vector<char>(system_.rows(), 1));
}

void Pcpg::begin(const Snapshot* warm) {
  d_ = system_.d(load_factor_);
  e_ = system_.e(load_factor_);
  lambda_ = coarse_.particular(e_);
  if (!space().any(!(warm && warm->dual.size() == lambda_.size()))) {
    // Keep the previous multipliers' part in ker G; restore G lambda = e for the new load.
    Eigen::VectorXd previous = warm->dual;
    coarse_.project(previous);
    lambda_ += previous;
  }
  system_.residual(lambda_, load_factor_, r_);
  set_scale();
  yw_previous_ = 0.0;
  reset_watch();
  record_residual();
}

void Pcpg::record_residual() {
  w_ = r_;
  coarse_.project(w_);
  system_.project_onto_range_of_B(w_);
  record(stopping_test(space().norm(w_)), 0);
}

void Pcpg::advance() {
  const PcpgStep step = pcpg_step(w_, nullptr, iteration_ == 0, yw_previous_, p_, q_);
  if (!step.ok) return;
  lambda_ += step.a * p_;
  update_residual(step.a, q_);
  yw_previous_ = step.yw;
  record_residual();
}

}  // namespace fetic::solver
