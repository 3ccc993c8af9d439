#include "app/method_options.hpp"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>

#include "scenes/message_text.hpp"
#include "solver/load_sweep.hpp"

namespace fetic::app {

solver::SolveOptions MethodArgs::options() const {
  solver::SolveOptions options;
  options.tolerance = tolerance;
  options.max_iterations = max_iterations;
  options.preconditioner = *solver::parse_preconditioner(preconditioner);
  options.scaling = !no_scaling;
  options.single_factors = single_factors;
  options.corner_clusters = clusters;
  options.edge_averages = primal == "corners+edges";
  return options;
}

std::vector<double> MethodArgs::load_factors() const {
  if (load_steps.empty()) return {load_factor};
  const LoadSteps steps = *parse_load_steps(load_steps);
  return solver::load_steps(steps.first, steps.last, steps.count);
}

std::optional<LoadSteps> parse_load_steps(const std::string& text) {
  const size_t colon1 = text.find(':');
  const size_t colon2 = colon1 == std::string::npos ? colon1 : text.find(':', colon1 + 1);
  if (colon2 == std::string::npos) return std::nullopt;
  const auto first = parse_number(text.substr(0, colon1));
  const auto last = parse_number(text.substr(colon1 + 1, colon2 - colon1 - 1));
  const std::string count = text.substr(colon2 + 1);
  char* end = nullptr;
  errno = 0;
  const long n = std::strtol(count.c_str(), &end, 10);
  if (!first || !last || count.empty() || end != count.c_str() + count.size() || errno != 0 ||
      n < 1 || n > 100000)
    return std::nullopt;
  return LoadSteps{*first, *last, static_cast<int>(n)};
}

namespace {

using scenes::number_text;
// Values are quoted back shortened and escaped: an option's message stays one line.
using scenes::shortened;

}  // namespace

CLI::Validator finite_number() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        return parse_number(text) ? "" : "must be a finite number, got " + shortened(text);
      },
      "FINITE");
}

CLI::Validator number_in(double low, double high, Bound low_bound, Bound high_bound) {
  std::string range;
  if (low_bound != Bound::None)
    range += (low_bound == Bound::Open ? " greater than " : " of at least ") + number_text(low);
  if (high_bound != Bound::None)
    range += std::string(range.empty() ? "" : " and") +
             (high_bound == Bound::Open ? " less than " : " of at most ") + number_text(high);
  const std::string description = "must be a finite number" + range;
  return CLI::Validator(
      [=](std::string& text) -> std::string {
        const auto value = parse_number(text);
        const bool fits = value &&
                          (low_bound == Bound::None ||
                           (low_bound == Bound::Open ? *value > low : *value >= low)) &&
                          (high_bound == Bound::None ||
                           (high_bound == Bound::Open ? *value < high : *value <= high));
        return fits ? "" : description + ", got " + shortened(text);
      },
      "NUMBER");
}

CLI::Validator integer_in(long long low, long long high) {
  return CLI::Validator(
      [=](std::string& text) -> std::string {
        char* end = nullptr;
        errno = 0;
        const long long value = std::strtoll(text.c_str(), &end, 10);
        if (!text.empty() && end == text.c_str() + text.size() && errno == 0 && value >= low &&
            value <= high)
          return "";
        return "must be a whole number from " + std::to_string(low) + " to " +
               std::to_string(high) + ", got " + shortened(text);
      },
      "INT");
}

CLI::Validator method_name() {
  return CLI::IsMember({"sd", "cg", "active-set", "feti", "feti-c", "mprgp", "feti-dp"});
}

CLI::Validator preconditioner_name() {
  return CLI::IsMember({"none", "lumped", "dirichlet"});
}

CLI::Option* add_method_option(CLI::App* command, std::string& method, const std::string& help) {
  return command->add_option("--method", method, help)->check(method_name())->capture_default_str();
}

CLI::Option* add_preconditioner_option(CLI::App* command, std::string& preconditioner,
                                       const std::string& help) {
  return command->add_option("--preconditioner", preconditioner, help)
      ->check(preconditioner_name())
      ->capture_default_str();
}

void add_method_options(CLI::App* command, MethodArgs& args) {
  add_method_option(command, args.method,
                    "Method: sd, cg, active-set, feti, feti-c, mprgp, feti-dp");
  CLI::Option* preconditioner = add_preconditioner_option(
      command, args.preconditioner,
      "FETI preconditioner (feti, feti-c, mprgp, feti-dp): none, lumped, dirichlet");
  CLI::Option* clusters =
      command
          ->add_option("--clusters", args.clusters,
                       "feti-dp: join the subdomains by their corners into clusters of about N "
                       "(hybrid FETI-DP; 1 is FETI-1); default: as large as the corners join them")
          ->check(integer_in(1, 1'000'000'000));
  CLI::Option* primal =
      command
          ->add_option("--primal", args.primal,
                       "feti-dp: the primal constraints, corners or corners+edges (plane "
                       "model: the average over every interface edge too)")
          ->check(CLI::IsMember({"corners", "corners+edges"}))
          ->capture_default_str();
  // A preconditioner asked for a method that has none would be silently ignored.
  command->parse_complete_callback([&args, preconditioner, clusters, primal] {
    const auto kind = solver::parse_method(args.method);
    if (preconditioner->count() > 0 && kind && !solver::is_dual(*kind))
      throw CLI::ValidationError("--preconditioner",
                                 "only feti, feti-c, mprgp and feti-dp have a preconditioner; " +
                                     args.method + " does not use one");
    if (clusters->count() > 0 && args.method != "feti-dp")
      throw CLI::ValidationError("--clusters", "only feti-dp joins subdomains into clusters; " +
                                                   args.method + " does not");
    if (primal->count() > 0 && args.method != "feti-dp")
      throw CLI::ValidationError(
          "--primal", "only feti-dp has primal constraints; " + args.method + " does not");
  });
  command->add_flag("--no-scaling", args.no_scaling,
                    "FETI preconditioners without stiffness scaling");
  command->add_flag("--single-factors", args.single_factors,
                    "Dual methods: subdomain factors' entries kept as floats (less memory)");
  // A relative tolerance of 1 or more lets the first iterate pass as converged.
  command->add_option("--tol", args.tolerance, "Relative tolerance, 0 < T < 1")
      ->check(number_in(0.0, 1.0, Bound::Open, Bound::Open))
      ->capture_default_str();
  command
      ->add_option("--max-iterations", args.max_iterations,
                   "Iteration cap (0: the method's default)")
      ->check(integer_in(0, 1'000'000'000));
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
