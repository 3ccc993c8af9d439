// End to end: `fetic solve` on bundled scenes writes the result file of SCENES.md and
// exits with the documented statuses.

#include <catch2/catch.hpp>

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "tests/support/shell_run.hpp"

namespace {

using Run = fetic::test::ShellRun;
using fetic::test::run;
using fetic::test::scene;
// A path in the temporary folder, unique to this test process.
const auto& temporary = fetic::test::temporary_path;

}  // namespace

TEST_CASE("fetic solve writes the result file of the contract") {
  const std::string json_path = temporary("fetic_thesis.json");
  std::filesystem::remove(json_path);
  const Run r = run("solve " + scene("thesis.toml") + " --method active-set --json " + json_path);
  INFO(r.output);
  REQUIRE(r.status == 0);
  CHECK_THAT(r.output, Catch::Contains("converged    yes"));
  std::ifstream in(json_path);
  const nlohmann::json result = nlohmann::json::parse(in);
  CHECK(result["model"] == "bar");
  CHECK(result["method"] == "active-set");
  CHECK(result["converged"] == true);
  CHECK(result["load_factor"] == 1.0);
  CHECK(result["struts"].size() == 100);
  CHECK(result["struts"][0]["name"] == "L01");
  CHECK(result["struts"][0]["nodes"].size() == 5);
  CHECK(result["struts"][0]["displacements"][0][0] == 0.0);  // clamped end
  CHECK(result["contacts"].size() == 50);
  CHECK(result["contacts"][0]["a"] == "L01.to");
  CHECK(result["contacts"][0]["pairs"].size() == 1);
  int active = 0;
  for (const auto& contact : result["contacts"]) {
    const auto& pair = contact["pairs"][0];
    CHECK(pair["force"].get<double>() >= 0.0);
    active += pair["active"].get<bool>() ? 1 : 0;
  }
  CHECK(active > 0);
  const auto& history = result["history"];
  REQUIRE(history.size() == result["iterations"].get<size_t>() + 1);
  CHECK(history[0]["iteration"] == 0);
  CHECK(history.back()["active_set"] == active);
  CHECK(result["units"]["length"] == "m");
  CHECK(result["units"]["stress"] == "Pa");
}

TEST_CASE("a scene in millimetres and newtons is reported in mm, N and MPa") {
  const std::string json_path = temporary("fetic_press_mm.json");
  const Run r = run("solve " + scene("press_mm.toml") + " --json " + json_path);
  INFO(r.output);
  REQUIRE(r.status == 0);
  CHECK_THAT(r.output, Catch::Contains("units        lengths in mm, forces in N, stresses in MPa"));
  CHECK_THAT(r.output, Catch::Contains(" mm (strut '"));
  std::ifstream in(json_path);
  const nlohmann::json result = nlohmann::json::parse(in);
  CHECK(result["units"] == nlohmann::json({{"length", "mm"}, {"force", "N"}, {"stress", "MPa"}}));
  // The numbers are the scene's own: the middle pair stays open (30 kN over 500 mm of
  // 100 mm² at 210000 N/mm² moves 0.71 mm, less than its 1 mm gap).
  const auto& open = result["contacts"][1]["pairs"][0];
  CHECK(!open["active"].get<bool>());
  const double tip = result["struts"][3]["displacements"][0][0].get<double>();
  CHECK(tip == Approx(-30000.0 * 500.0 / (210000.0 * 100.0)).epsilon(1e-6));
}

TEST_CASE("fetic solve on a frame adds the rotations and names contacts at any node") {
  const std::string json_path = temporary("fetic_frame.json");
  std::filesystem::remove(json_path);
  const Run r = run("solve " + scene("frame_beam_on_contacts.toml") + " --json " + json_path);
  INFO(r.output);
  REQUIRE(r.status == 0);
  std::ifstream in(json_path);
  const nlohmann::json result = nlohmann::json::parse(in);
  CHECK(result["model"] == "frame");
  CHECK(result["method"] == "feti-c");
  const auto& beam = result["struts"][0];
  CHECK(beam["name"] == "beam");
  REQUIRE(beam["rotations"].size() == beam["nodes"].size());
  // The floating beam sags between its posts: its ends turn opposite ways.
  CHECK(beam["rotations"][0].get<double>() * beam["rotations"][16].get<double>() < 0.0);
  CHECK(result["contacts"][0]["b"] == "beam@2");
  for (const auto& contact : result["contacts"]) {
    REQUIRE(contact["pairs"].size() == 1);
    CHECK(contact["pairs"][0]["active"] == true);
  }
  // The push of 5 kN at the beam's end is what the stop takes.
  CHECK(result["contacts"][2]["pairs"][0]["force"].get<double>() == Approx(5.0e3).epsilon(1e-8));
  std::filesystem::remove(json_path);
}

TEST_CASE("fetic solve refuses a frame mechanism with status 2, naming the struts") {
  const std::string path = temporary("mechanism.toml");
  {
    std::ofstream out(path);
    out << "model = \"frame\"\n[[strut]]\nname = \"swing\"\nfrom = [0.0, 0.0]\n"
           "to = [0.0, -1.0]\nE = 2e11\narea = 1e-3\ninertia = 1e-6\nelements = 2\n"
           "pinned = [\"from\"]\n";
  }
  const Run r = run("solve " + path);
  CHECK(r.status == 2);
  CHECK_THAT(r.output, Catch::Contains(path + ":2: strut 'swing' is a mechanism") &&
                           Catch::Contains("rotate about (0, 0)"));
  std::filesystem::remove(path);
}

TEST_CASE("fetic solve exit statuses: invalid scene 2, unsupported method 3, no convergence 4") {
  const Run invalid = run("solve " + std::string(FETIC_BUNDLED_SCENES_DIR) +
                          "/../tests/scenes/invalid/strut_negative_E.toml");
  CHECK(invalid.status == 2);
  CHECK_THAT(invalid.output,
             Catch::Contains("strut_negative_E.toml:8: strut 'A': 'E' must be greater than 0"));

  const Run missing = run("solve no_such_scene.toml");
  CHECK(missing.status == 2);
  CHECK_THAT(missing.output, Catch::Contains("no_such_scene.toml: cannot open the scene file"));

  const Run refused = run("solve " + scene("two_bars.toml") + " --method cg");
  CHECK(refused.status == 3);
  CHECK_THAT(refused.output, Catch::Contains("two_bars.toml: conjugate gradients"));

  const std::string json_path = temporary("fetic_unconverged.json");
  std::filesystem::remove(json_path);
  const Run capped = run("solve " + scene("cantilevers.toml") +
                         " --method sd --max-iterations 5 --json " + json_path);
  CHECK(capped.status == 4);
  CHECK_THAT(capped.output, Catch::Contains("no convergence within 5 iterations"));
  std::ifstream in(json_path);
  REQUIRE(in.good());  // the result file is still written
  const nlohmann::json result = nlohmann::json::parse(in);
  CHECK(result["converged"] == false);
  CHECK(result["history"].size() == 6);
}

TEST_CASE("fetic solve rejects bad command lines with status 1") {
  CHECK(run("solve " + scene("two_bars.toml") + " --method newton").status == 1);
  CHECK(run("solve " + scene("two_bars.toml") + " --load-factor nan").status == 1);
  CHECK(run("frobnicate").status == 1);
  // A preconditioner for a method that has none is refused, not silently ignored.
  const Run preconditioned =
      run("solve " + scene("two_bars.toml") + " --method active-set --preconditioner lumped");
  CHECK(preconditioned.status == 1);
  CHECK(preconditioned.output.find("only feti, feti-c, mprgp and feti-dp have a preconditioner") !=
        std::string::npos);
  CHECK(run("solve " + scene("two_bars.toml") + " --method feti-c --preconditioner lumped --quiet")
            .status == 0);
}

TEST_CASE("fetic solve --method feti-c --reference records the error of every iteration") {
  const std::string json_path = temporary("fetic_reference.json");
  const Run r =
      run("solve " + scene("thesis.toml") + " --method feti-c --reference --json " + json_path);
  INFO(r.output);
  REQUIRE(r.status == 0);
  std::ifstream in(json_path);
  const nlohmann::json result = nlohmann::json::parse(in);
  CHECK(result["method"] == "feti-c");
  CHECK(result["preconditioner"] == "dirichlet");
  const auto& history = result["history"];
  REQUIRE(history.size() >= 2);
  CHECK(history[0]["error"].get<double>() > 1e-3);
  CHECK(history.back()["error"].get<double>() < 1e-8);
  CHECK(history[0]["active_set"] == 50);  // FETI-C starts with every contact in W
}

TEST_CASE("fetic solve --method mprgp: errors and applications of F in the history") {
  const std::string json_path = temporary("fetic_mprgp.json");
  const Run r =
      run("solve " + scene("plane_pair.toml") + " --method mprgp --reference --json " + json_path);
  INFO(r.output);
  REQUIRE(r.status == 0);
  CHECK_THAT(r.output, Catch::Contains("mprgp (preconditioner dirichlet)"));
  std::ifstream in(json_path);
  const nlohmann::json result = nlohmann::json::parse(in);
  CHECK(result["method"] == "mprgp");
  CHECK(result["preconditioner"] == "dirichlet");
  const auto& history = result["history"];
  REQUIRE(history.size() >= 2);
  CHECK(history.back()["error"].get<double>() < 1e-8);
  // Every iteration applies F at least once.
  for (size_t k = 1; k < history.size(); ++k)
    CHECK(history[k]["f_applications"].get<int>() > history[k - 1]["f_applications"].get<int>());
}

TEST_CASE("fetic solve --load-steps sweeps with warm starts and reports every step") {
  const std::string json_path = temporary("fetic_steps.json");
  const Run r =
      run("solve " + scene("thesis.toml") + " --load-steps 0.9:1.1:5 --json " + json_path);
  INFO(r.output);
  REQUIRE(r.status == 0);
  CHECK_THAT(r.output, Catch::Contains("load steps   5 from 0.9 to 1.1"));
  std::ifstream in(json_path);
  const nlohmann::json result = nlohmann::json::parse(in);
  REQUIRE(result["steps"].size() == 5);
  CHECK(result["steps"][4]["load_factor"] == 1.1);
  CHECK(result["load_factor"] == 1.1);  // the contract's keys describe the last step
  int total = 0;
  for (const auto& step : result["steps"]) {
    CHECK(step["converged"] == true);
    total += step["iterations"].get<int>();
  }
  CHECK(total < 5 * 6);  // fewer than five cold FETI-C solves
  CHECK(run("solve " + scene("thesis.toml") + " --load-steps 1:2").status == 1);
  CHECK(run("solve " + scene("thesis.toml") + " --load-steps 1:2:3 --load-factor 2").status == 1);
}

TEST_CASE("fetic bench prints a table with ratios to the active-set method") {
  const std::string csv = temporary("fetic_bench.csv");
  const Run r = run("bench " + scene("two_bars.toml") + " --repeat 1 --csv " + csv);
  INFO(r.output);
  REQUIRE(r.status == 0);
  CHECK_THAT(r.output, Catch::Contains("solve/AS") && Catch::Contains("feti-c/dirichlet"));
  std::ifstream in(csv);
  std::string header;
  std::getline(in, header);
  CHECK(header.rfind("scene,method,unknowns,iterations", 0) == 0);
}

TEST_CASE("solve --profile: per process counts, and MPRGP's iterations by step kind") {
  for (const std::string method : {"feti-c", "mprgp", "feti-dp"}) {
    const std::string profile_path = temporary("fetic_profile_" + method + ".json");
    const std::string json_path = temporary("fetic_profile_result_" + method + ".json");
    const Run r = run("solve " + scene("plane_pair.toml") + " --method " + method +
                      " --quiet --profile " + profile_path + " --json " + json_path);
    INFO(method << "\n" << r.output);
    REQUIRE(r.status == 0);
    std::ifstream in(profile_path);
    const nlohmann::json profile = nlohmann::json::parse(in);
    std::ifstream result_in(json_path);
    const nlohmann::json result = nlohmann::json::parse(result_in);
    CHECK(profile["ranks"] == 1);
    CHECK(profile["iterations"] == result["iterations"]);
    REQUIRE(profile["processes"].size() == 1);
    const nlohmann::json& process = profile["processes"][0];
    // The subdomains' DOFs: the scene's 340 plus a copy of every interface node's.
    CHECK(process["unknowns"].get<double>() > 340.0);
    CHECK(process["f_applications"].get<double>() >= profile["iterations"].get<double>());
    // The solve's time by part (the Dirichlet preconditioner is applied at least once
    // per iteration of each method).
    for (const char* part : {"local_seconds", "coarse_seconds", "preconditioner_seconds",
                             "mode_product_seconds", "range_projection_seconds"})
      CHECK(process[part].get<double>() >= 0.0);
    CHECK(process["preconditioner_seconds"].get<double>() > 0.0);
    CHECK(process["preconditioner_applications"].get<double>() > 0.0);
    // Bytes read per application: at most what the factors and blocks hold, read twice.
    CHECK(process["f_bytes_read"].get<double>() > 0.0);
    CHECK(process["f_bytes_read"].get<double>() <=
          2.0 * process["subdomain_factor_bytes"].get<double>());
    CHECK(process["preconditioner_bytes_read"].get<double>() > 0.0);
    CHECK(process["preconditioner_bytes_read"].get<double>() <=
          2.0 * (process["subdomain_factor_bytes"].get<double>() +
                 process["preconditioner_factor_bytes"].get<double>() +
                 process["preconditioner_block_bytes"].get<double>()));
    // The Lanczos estimate of the longest CG run: Ritz values of an SPD operator.
    const nlohmann::json& condition = profile["condition_estimate"];
    CHECK(condition["cg_steps"].get<int>() > 0);
    CHECK(condition["cg_steps"].get<int>() <= profile["iterations"].get<int>());
    CHECK(condition["lambda_min"].get<double>() > 0.0);
    CHECK(condition["kappa"].get<double>() >= 1.0);
    CHECK(condition["kappa"].get<double>() ==
          Approx(condition["lambda_max"].get<double>() / condition["lambda_min"].get<double>()));
    if (method == "feti-c") {
      CHECK(!profile.contains("mprgp_steps"));
    } else {
      // Every MPRGP iteration is one conjugate gradient, expansion or proportioning step.
      const nlohmann::json& steps = profile["mprgp_steps"];
      CHECK(steps["conjugate_gradient"].get<int>() + steps["expansion"].get<int>() +
                steps["proportioning"].get<int>() ==
            profile["iterations"].get<int>());
      CHECK(steps["conjugate_gradient"].get<int>() > 0);
      CHECK(steps["outer"].get<int>() == 0);  // plane struts are clamped: no SMALBE groups
      // FETI-DP: a uniform and a linear column per contact and pair of boxes its rows
      // cross (2 boxes across each strut: 2 segments), one F each at set-up (all on the same
      // two clusters, so no two share an application: solver/contact_batches.hpp).
      const int columns = method == "feti-dp" ? 4 : 0;
      CHECK(profile.value("contact_coarse_columns", 0) == columns);
      CHECK(profile["setup_f_applications"].get<int>() > columns);
    }
    std::filesystem::remove(profile_path);
    std::filesystem::remove(json_path);
  }
}

namespace {

// The string `field` of the --profile of a small solve started under `environment` (an
// `env ...` prefix): what the process itself saw after fetic's start-up (app/main.cpp).
std::string profile_string(const std::string& environment, const std::string& field) {
  const std::string profile_path = temporary("fetic_profile_start_up.json");
  const Run r =
      fetic::test::run_shell(environment + " " + std::string(FETIC_EXECUTABLE) + " solve " +
                             scene("thesis.toml") + " --quiet --profile " + profile_path);
  INFO(r.output);
  REQUIRE(r.status == 0);
  std::ifstream in(profile_path);
  const std::string value = nlohmann::json::parse(in)[field].get<std::string>();
  std::filesystem::remove(profile_path);
  return value;
}

}  // namespace

TEST_CASE("fetic starts its OpenMP threads passive unless OMP_WAIT_POLICY is given") {
  const auto policy_of = [](const std::string& environment) {
    return profile_string(environment, "openmp_wait_policy");
  };
  // Spinning threads make a solve several times slower when another process holds a core.
  CHECK(policy_of("env -u OMP_WAIT_POLICY") == "passive");
  CHECK(policy_of("env OMP_WAIT_POLICY=active") == "active");  // the user's choice wins
}

TEST_CASE("fetic asks glibc's malloc for huge pages unless GLIBC_TUNABLES names hugetlb") {
  const auto tunables_of = [](const std::string& environment) {
    return profile_string(environment, "glibc_tunables");
  };
  // Each first touch of a 4 KiB heap page costs 10-30 us on the machines measured (main.cpp).
  CHECK(tunables_of("env -u OMP_WAIT_POLICY -u GLIBC_TUNABLES") == "glibc.malloc.hugetlb=1");
  // Other tunables of the user's are kept; a hugetlb setting of the user's wins.
  CHECK(tunables_of("env -u OMP_WAIT_POLICY GLIBC_TUNABLES=glibc.malloc.arena_max=2") ==
        "glibc.malloc.arena_max=2:glibc.malloc.hugetlb=1");
  CHECK(tunables_of("env -u OMP_WAIT_POLICY GLIBC_TUNABLES=glibc.malloc.hugetlb=0") ==
        "glibc.malloc.hugetlb=0");
}
