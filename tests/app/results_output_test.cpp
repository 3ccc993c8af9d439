// End to end: what `fetic solve` writes for post-processing - the load-step result file
// and CSV table of scenes/two_bars.toml against the closed form (a load-contact-force and
// a load-displacement curve, piecewise linear with the kink where the gap closes), the
// layout of the result file, and the summary's wording.

#include <catch2/catch.hpp>

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include <nlohmann/json.hpp>

#include "tests/support/shell_run.hpp"

namespace {

using Run = fetic::test::ShellRun;
using fetic::test::run;
using fetic::test::scene;
// A path in the temporary folder, unique to this test process.
const auto& temporary = fetic::test::temporary_path;

// scenes/two_bars.toml: EA = 2.1e7 N, both bars 1 m, gap 1 mm, P = 63 kN at t = 1, the
// load at right.from; the gap closes at t* = g EA / (P L) = 1/3.
struct TwoBars {
  double EA = 2.1e11 * 1e-4, L = 1.0, gap = 0.001, P = 63000.0;
  double force(double t) const { return std::max(0.0, (t * P * L / EA - gap) / (2 * L / EA)); }
  double right_from_ux(double t) const { return -(t * P - force(t)) * L / EA; }
  double left_to_ux(double t) const { return -force(t) * L / EA; }
};

std::vector<std::map<std::string, std::string>> read_csv(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  std::vector<std::string> header;
  std::stringstream head(line);
  for (std::string cell; std::getline(head, cell, ',');)
    header.push_back(cell);
  std::vector<std::map<std::string, std::string>> rows;
  while (std::getline(in, line)) {
    std::stringstream row(line);
    std::map<std::string, std::string> values;
    size_t column = 0;
    for (std::string cell; std::getline(row, cell, ',') && column < header.size(); ++column)
      values[header[column]] = cell;
    rows.push_back(values);
  }
  return rows;
}

}  // namespace

TEST_CASE("two bars load sweep: contact force and displacement curves match the closed form") {
  const std::string json_path = temporary("two_bars_steps.json");
  const std::string steps_csv = temporary("two_bars_steps.csv");
  const std::string history_csv = temporary("two_bars_history.csv");
  const Run r = run("solve " + scene("two_bars.toml") + " --load-steps 0:2:13 --tol 1e-12 --json " +
                    json_path + " --csv-steps " + steps_csv + " --csv " + history_csv);
  INFO(r.output);
  REQUIRE(r.status == 0);
  std::ifstream in(json_path);
  const auto result = nlohmann::ordered_json::parse(in);
  const TwoBars closed;
  const double force_scale = closed.P, u_scale = closed.P * closed.L / closed.EA;
  const auto& steps = result["steps"];
  REQUIRE(steps.size() == 13);
  int before = 0, after = 0;
  for (const auto& step : steps) {
    const double t = step["load_factor"].get<double>();
    INFO("t = " << t);
    // Every step carries the full result in the shape of the top level.
    for (const char* key :
         {"converged", "iterations", "struts", "contacts", "reactions", "history"})
      CHECK(step.contains(key));
    CHECK(step["converged"] == true);
    CHECK(step["interrupted"] == false);
    const double force = step["contacts"][0]["pairs"][0]["force"].get<double>();
    CHECK(std::abs(force - closed.force(t)) <= 1e-8 * force_scale);
    CHECK(std::abs(step["contacts"][0]["force"].get<double>() - force) == 0.0);
    CHECK(step["contacts"][0]["pairs"][0]["active"] == (closed.force(t) > 0.0));
    const double right = step["struts"][1]["displacements"][0][0].get<double>();
    const double left = step["struts"][0]["displacements"][4][0].get<double>();
    CHECK(std::abs(right - closed.right_from_ux(t)) <= 1e-8 * u_scale);
    CHECK(std::abs(left - closed.left_to_ux(t)) <= 1e-8 * u_scale);
    // Reactions: the left clamp takes the contact force, the right one the rest.
    CHECK(step["reactions"][0]["support"] == "left.from");
    CHECK(std::abs(step["reactions"][0]["force"][0].get<double>() - closed.force(t)) <=
          1e-8 * force_scale);
    CHECK(std::abs(step["reactions"][1]["force"][0].get<double>() -
                   (t * closed.P - closed.force(t))) <= 1e-8 * force_scale);
    (t < 1.0 / 3.0 ? before : after) += 1;
  }
  // The kink: the force is zero while the gap is open, then rises with slope P/2; the
  // right tip moves with slope P L/EA, then half of it.
  CHECK(before >= 2);
  CHECK(after >= 2);
  const auto slope = [&](const char* what, size_t i) {
    const auto value = [&](size_t k) {
      const auto& step = steps[k];
      return std::string(what) == "force" ? step["contacts"][0]["force"].get<double>()
                                          : step["struts"][1]["displacements"][0][0].get<double>();
    };
    return (value(i + 1) - value(i)) /
           (steps[i + 1]["load_factor"].get<double>() - steps[i]["load_factor"].get<double>());
  };
  CHECK(std::abs(slope("force", 0)) <= 1e-8 * force_scale);
  CHECK(std::abs(slope("force", 11) - closed.P / 2) <= 1e-7 * force_scale);
  CHECK(std::abs(slope("ux", 0) + closed.P * closed.L / closed.EA) <= 1e-7 * u_scale);
  CHECK(std::abs(slope("ux", 11) + closed.P * closed.L / closed.EA / 2) <= 1e-7 * u_scale);

  // The same curve in the load-step table; default nodes: both ends of every contact.
  const auto rows = read_csv(steps_csv);
  REQUIRE(rows.size() == 13);
  for (const auto& row : rows) {
    const double t = std::stod(row.at("load_factor"));
    CHECK(row.at("status") == "converged");
    CHECK(std::abs(std::stod(row.at("force:left.to/right.from [N]")) - closed.force(t)) <=
          1e-8 * force_scale);
    CHECK(std::abs(std::stod(row.at("ux:right.from [m]")) - closed.right_from_ux(t)) <=
          1e-8 * u_scale);
    CHECK(std::abs(std::stod(row.at("ux:left.to [m]")) - closed.left_to_ux(t)) <= 1e-8 * u_scale);
    CHECK(std::stoi(row.at("active_pairs:left.to/right.from")) == (closed.force(t) > 0.0 ? 1 : 0));
  }
  // The history table: one row per history entry of every step.
  size_t entries = 0;
  for (const auto& step : steps)
    entries += step["history"].size();
  const auto history = read_csv(history_csv);
  CHECK(history.size() == entries);
  CHECK(history.back().at("load_step") == "12");
}

TEST_CASE("result file: plain values first, pair geometry, element data, exact clamped zeros") {
  const std::string json_path = temporary("plane_pair.json");
  const Run r = run("solve " + scene("plane_pair.toml") + " --json " + json_path);
  INFO(r.output);
  REQUIRE(r.status == 0);
  std::ifstream in(json_path);
  const auto result = nlohmann::ordered_json::parse(in);
  bool structured_seen = false;
  for (const auto& [key, value] : result.items()) {
    INFO(key);
    if (value.is_structured())
      structured_seen = true;
    else
      CHECK_FALSE(structured_seen);
  }
  CHECK(result["interrupted"] == false);
  const auto& strut = result["struts"][0];
  const size_t elements = 16 * 4;
  CHECK(strut["elements"].size() == elements);
  CHECK(strut["elements"][0].size() == 4);
  CHECK(strut["element_subdomains"].size() == elements);
  for (const char* name : {"axial", "sxx", "syy", "sxy", "von_mises"})
    CHECK(strut["stress"][name].size() == elements);
  CHECK(strut["axial_force"].size() == elements);
  // The left strut is clamped at 'from': nodes 0..4 are exactly zero.
  for (int n = 0; n <= 4; ++n) {
    CHECK(strut["displacements"][n][0].get<double>() == 0.0);
    CHECK(strut["displacements"][n][1].get<double>() == 0.0);
  }
  const auto& contact = result["contacts"][0];
  REQUIRE(contact["pairs"].size() == 5);
  for (size_t k = 0; k < 5; ++k) {
    const auto& pair = contact["pairs"][k];
    const int a = pair["node_a"].get<int>(), b = pair["node_b"].get<int>();
    CHECK(pair["point_a"] == result["struts"][0]["nodes"][a]);
    CHECK(pair["point_b"] == result["struts"][1]["nodes"][b]);
    CHECK(pair["normal"][0].get<double>() == Approx(1.0));
    const double gap = pair["point_b"][0].get<double>() - pair["point_a"][0].get<double>();
    CHECK(pair["gap"].get<double>() == Approx(gap).margin(1e-12));
  }
  REQUIRE(result["reactions"].size() == 2);
  CHECK(result["reactions"][0]["nodes"].size() == 5);
}

TEST_CASE("summary: singular and plural counts") {
  const Run r = run("solve " + scene("two_bars.toml") + " --method active-set");
  INFO(r.output);
  REQUIRE(r.status == 0);
  CHECK_THAT(r.output, Catch::Contains("2 struts, 1 contact, 10 unknowns"));
  CHECK_THAT(r.output, Catch::Contains("1 of 1 node pair active"));
  CHECK_THAT(r.output,
             Catch::Contains("after 1 iteration,") || Catch::Contains("after 2 iterations,"));
}

TEST_CASE("solve with a bad --csv-node is a usage error naming the problem") {
  const Run r = run("solve " + scene("two_bars.toml") + " --csv-steps " + temporary("x.csv") +
                    " --csv-node nobody.to");
  CHECK(r.status == 1);
  CHECK_THAT(r.output, Catch::Contains("the scene has no strut 'nobody'"));
  const Run range = run("solve " + scene("two_bars.toml") + " --csv-node left@9");
  CHECK(range.status == 1);
  CHECK_THAT(range.output, Catch::Contains("strut 'left' has nodes 0..4"));
}

TEST_CASE("every command's --help ends with an example, its exit statuses and units") {
  for (const char* command :
       {"solve", "render", "figures", "bench", "bench-render", "gui", "generate"}) {
    INFO(command);
    const Run r = run(std::string(command) + " --help");
    CHECK(r.status == 0);
    CHECK_THAT(r.output, Catch::Contains("Example"));
    CHECK_THAT(r.output, Catch::Contains("fetic " + std::string(command) + " "));
    CHECK_THAT(r.output, Catch::Contains("Exit status:"));
    CHECK_THAT(r.output, Catch::Contains("  0    success"));
    CHECK_THAT(r.output, Catch::Contains("pixels") || Catch::Contains("[m]") ||
                             Catch::Contains("milliseconds"));
  }
}
