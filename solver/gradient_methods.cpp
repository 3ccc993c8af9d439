#include "solver/gradient_methods.hpp"

#include <cmath>

namespace fetic::solver {
namespace {

void refuse_contacts(const Model& model, MethodKind kind) {
  if (!model.pairs.empty())
    throw SolverError(std::string(kind == MethodKind::SteepestDescent ? "steepest descent"
                                                                      : "conjugate gradients") +
                      " (--method " + to_string(kind) + ") solves scenes without contacts; " +
                      "this scene has " + std::to_string(model.contact_labels.size()) +
                      " contact(s): use --method active-set or --method feti-c");
}

}  // namespace

GradientMethod::GradientMethod(const Model& model, const SolveOptions& options,
                               int default_max_iterations, MethodKind kind)
    : Method(kind, model, options, default_max_iterations),
      problem_((refuse_contacts(model, kind), model)) {}

void GradientMethod::begin(const Snapshot* warm) {
  const double load_factor = load_factor_;
  x_ = Eigen::VectorXd::Zero(problem_.size());
  if (warm && warm->primal.size() == problem_.size()) x_ = warm->primal;
  r_ = load_factor * problem_.load() - problem_.stiffness() * x_;
  rhs_norm_ = std::abs(load_factor) * problem_.load().norm();
  record_residual();
}

void GradientMethod::record_residual() {
  const double residual = rhs_norm_ > 0.0 ? r_.norm() / rhs_norm_ : r_.norm();
  if (residual <= options_.tolerance || r_.norm() == 0.0) converge();
  record(residual, 0);
}

Snapshot GradientMethod::snapshot() const {
  Snapshot s = snapshot_header();
  s.pieces = problem_.pieces(x_);
  s.primal = x_;
  return s;
}

SteepestDescent::SteepestDescent(const Model& model, const SolveOptions& options)
    : GradientMethod(model, options, 1'000'000, MethodKind::SteepestDescent) {}

void SteepestDescent::advance() {
  const Eigen::VectorXd Kr = problem_.stiffness() * r_;
  const double alpha = r_.squaredNorm() / r_.dot(Kr);
  x_ += alpha * r_;
  r_ -= alpha * Kr;
  ++iteration_;
  record_residual();
}

ConjugateGradient::ConjugateGradient(const Model& model, const SolveOptions& options)
    : GradientMethod(model, options, 0, MethodKind::ConjugateGradient) {
  // Exact arithmetic needs at most n steps; rounding may need a few times more.
  if (options.max_iterations <= 0) max_iterations_ = 10 * problem_.size() + 100;
}

void ConjugateGradient::begin(const Snapshot* warm) {
  GradientMethod::begin(warm);
  direction_ = r_;
}

void ConjugateGradient::advance() {
  const Eigen::VectorXd Kd = problem_.stiffness() * direction_;
  const double rr = r_.squaredNorm();
  const double alpha = rr / direction_.dot(Kd);
  x_ += alpha * direction_;
  r_ -= alpha * Kd;
  const double beta = r_.squaredNorm() / rr;
  direction_ = r_ + beta * direction_;
  ++iteration_;
  record_residual();
}

}  // namespace fetic::solver
