#include "app/method_options.hpp"

#include <cmath>
#include <sstream>

#include "solver/load_sweep.hpp"

namespace fetic::app {

solver::SolveOptions MethodArgs::options() const {
  solver::SolveOptions options;
  options.tolerance = tolerance;
  options.max_iterations = max_iterations;
  options.preconditioner = *solver::parse_preconditioner(preconditioner);
  options.scaling = !no_scaling;
  return options;
}

std::vector<double> MethodArgs::load_factors() const {
  if (load_steps.empty()) return {load_factor};
  const LoadSteps steps = *parse_load_steps(load_steps);
  return solver::load_steps(steps.first, steps.last, steps.count);
}

std::optional<LoadSteps> parse_load_steps(const std::string& text) {
  std::istringstream in(text);
  LoadSteps steps;
  char colon1 = 0, colon2 = 0;
  if (!(in >> steps.first >> colon1 >> steps.last >> colon2 >> steps.count) || colon1 != ':' ||
      colon2 != ':')
    return std::nullopt;
  in >> std::ws;
  if (!in.eof() || !std::isfinite(steps.first) || !std::isfinite(steps.last) || steps.count < 1 ||
      steps.count > 100000)
    return std::nullopt;
  return steps;
}

CLI::Validator finite_number() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        try {
          size_t used = 0;
          const double value = std::stod(text, &used);
          if (used == text.size() && std::isfinite(value)) return {};
        } catch (const std::exception&) {
        }
        return "must be a finite number, got " + text;
      },
      "FINITE");
}

CLI::Validator method_name() {
  return CLI::IsMember({"sd", "cg", "active-set", "feti", "feti-c", "mprgp"});
}

CLI::Validator preconditioner_name() {
  return CLI::IsMember({"none", "lumped", "dirichlet"});
}

void add_method_options(CLI::App* command, MethodArgs& args) {
  command->add_option("--method", args.method, "Method: sd, cg, active-set, feti, feti-c, mprgp")
      ->check(method_name())
      ->capture_default_str();
  CLI::Option* preconditioner =
      command
          ->add_option("--preconditioner", args.preconditioner,
                       "FETI preconditioner (feti, feti-c, mprgp): none, lumped, dirichlet")
          ->check(preconditioner_name())
          ->capture_default_str();
  // A preconditioner asked for a method that has none would be silently ignored.
  command->parse_complete_callback([&args, preconditioner] {
    const auto kind = solver::parse_method(args.method);
    if (preconditioner->count() > 0 && kind && !solver::is_dual(*kind))
      throw CLI::ValidationError("--preconditioner",
                                 "only feti, feti-c and mprgp have a preconditioner; " +
                                     args.method + " does not use one");
  });
  command->add_flag("--no-scaling", args.no_scaling,
                    "FETI preconditioners without stiffness scaling");
  command->add_option("--tol", args.tolerance, "Relative tolerance")
      ->check(CLI::PositiveNumber)
      ->check(finite_number())
      ->capture_default_str();
  command
      ->add_option("--max-iterations", args.max_iterations,
                   "Iteration cap (0: the method's default)")
      ->check(CLI::NonNegativeNumber);
  auto* factor = command->add_option("--load-factor", args.load_factor, "Global load factor t")
                     ->check(finite_number())
                     ->capture_default_str();
  command
      ->add_option("--load-steps", args.load_steps,
                   "Sweep the load factor: a:b:n (n values from a to b), each solve "
                   "warm-started from the previous")
      ->check(CLI::Validator(
          [](std::string& text) -> std::string {
            return parse_load_steps(text) ? ""
                                          : "must be a:b:n with finite a, b and 1 <= n <= 100000";
          },
          "A:B:N"))
      ->excludes(factor);
}

}  // namespace fetic::app
