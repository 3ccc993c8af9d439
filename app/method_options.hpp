#pragma once
// Command-line options every solving command shares: method, preconditioner, tolerance,
// iteration cap, load factor or load steps.

#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "app/parse_number.hpp"
#include "solver/method.hpp"

namespace fetic::app {

struct MethodArgs {
  std::string method = "feti-c";
  std::string preconditioner = "dirichlet";
  bool no_scaling = false;
  bool single_factors = false;  // --single-factors
  int clusters = 0;  // feti-dp: clusters of about N subdomains (0: as large as corners join)
  std::string primal = "corners";  // feti-dp: corners | corners+edges (--primal)
  double tolerance = 1e-10;
  int max_iterations = 0;
  double load_factor = 1.0;
  std::string load_steps;  // "a:b:n", empty when not given

  solver::MethodKind kind() const { return *solver::parse_method(method); }
  solver::SolveOptions options() const;
  // The load factors to solve at: the load steps when given, else the load factor.
  std::vector<double> load_factors() const;
};

void add_method_options(CLI::App* command, MethodArgs& args);

// "a:b:n" -> (a, b, n), or nullopt.
struct LoadSteps {
  double first = 0.0, last = 1.0;
  int count = 1;
};
std::optional<LoadSteps> parse_load_steps(const std::string& text);

// CLI11 checks with short messages that name the range (CLI11's own print the bounds of
// an unbounded range with all 309 digits of the largest double).
CLI::Validator finite_number();
enum class Bound { None, Open, Closed };
// A finite number within the bounds: number_in(0, 1, Bound::Open, Bound::Open) is 0 < x < 1.
CLI::Validator number_in(double low, double high, Bound low_bound, Bound high_bound);
// A whole number low..high.
CLI::Validator integer_in(long long low, long long high);

// CLI11 checks that a value names a method / a FETI preconditioner, for every command that
// lets the user choose one.
CLI::Validator method_name();
CLI::Validator preconditioner_name();

// --method and --preconditioner, so checked and with the default shown in --help, for the
// commands that take them with help of their own (add_method_options adds both too).
CLI::Option* add_method_option(CLI::App* command, std::string& method, const std::string& help);
CLI::Option* add_preconditioner_option(CLI::App* command, std::string& preconditioner,
                                       const std::string& help);

}  // namespace fetic::app
