// Hostile command lines and scene files through the real program: every case ends with
// its documented status and a message that names the problem (docs/COMMANDS.md).

#include <catch2/catch.hpp>

#include <sys/stat.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>

#include <nlohmann/json.hpp>

#include "tests/support/process.hpp"
#include "tests/support/scene_toml.hpp"

using namespace fetic::test;
namespace fs = std::filesystem;

namespace {

const std::string kScene = bundled_scene("two_bars.toml");

// Every line of stderr is one message: no digits of the largest double, no empty lines.
void check_short_lines(const std::string& err) {
  size_t start = 0;
  while (start < err.size()) {
    const size_t end = std::min(err.find('\n', start), err.size());
    CHECK(end - start < 400);
    start = end + 1;
  }
  CHECK(err.find("179769313486231570") == std::string::npos);
}

}  // namespace

TEST_CASE("option values out of range: status 1, the option, the range and the value",
          "[hostile]") {
  struct Case {
    std::vector<std::string> command;
    std::string message;
  };
  const std::vector<Case> cases = {
      {{"solve", kScene, "--tol", "1e300"},
       "--tol: must be a finite number greater than 0 and less than 1, got 1e300"},
      {{"solve", kScene, "--tol", "0"}, "--tol: must be a finite number greater than 0"},
      {{"solve", kScene, "--max-iterations", "-5"},
       "--max-iterations: must be a whole number from 0 to 1000000000, got -5"},
      {{"render", kScene, "--out", "unused", "--max-frames", "0"},
       "--max-frames: must be a whole number from 1 to 1000000, got 0"},
      {{"gui", kScene, "--load", "nan"}, "--load: must be a finite number of at least 0, got nan"},
      {{"gui", kScene, "--max-load", "-1"}, "--max-load: must be a finite number of at least 0"},
      {{"render", kScene, "--out", "unused", "--magnification", "inf"}, "--magnification"},
      {{"solve", kScene, "--load-factor", "1e-320"},
       "--load-factor 9.99989e-321: times the load on strut 'right'"},
      {{"solve", kScene, "--load-factor", "1e+300"}, "outside the range double precision"},
      {{"solve", kScene, "--load-steps", "-1e308:1e308:3"}, "--load-steps -1e+308: times the load"},
      {{"solve", kScene, "--load-steps", "0:1:0"}, "must be a:b:n"},
      {{"frobnicate"}, "fetic: unknown command 'frobnicate' (commands: solve, "},
  };
  for (const Case& c : cases) {
    INFO(c.command[0] << " " << c.command.back());
    const Result r = run_fetic(c.command);
    INFO(r.err);
    CHECK(r.status == 1);
    CHECK_THAT(r.err, Catch::Contains(c.message));
    check_short_lines(r.err);
  }
  CHECK_FALSE(fs::exists("unused"));
}

TEST_CASE("a scene path with a newline keeps every message on one line", "[hostile]") {
  TempDir dir;
  const std::string path = dir / "two\nlines.toml";
  { std::ofstream(path) << "model = \"bar\"\nstrut = 3\n"; }
  const Result r = run_fetic({"solve", path});
  CHECK(r.status == 2);
  const std::string shown = (dir.path() / "two\\nlines.toml").string();
  CHECK_THAT(r.err, Catch::StartsWith(shown + ":2: 'strut' must be an array of tables"));
  CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
}

TEST_CASE("a directory as the scene, for every command that reads one: status 2", "[hostile]") {
  TempDir dir;
  for (const std::vector<std::string>& command :
       {std::vector<std::string>{"solve", dir.path().string()},
        {"bench", dir.path().string(), "--repeat", "1"}}) {
    const Result r = run_fetic(command);
    CHECK(r.status == 2);
    CHECK(r.err == dir.path().string() + ": is a directory, not a scene file\n");
  }
}

TEST_CASE("SIGTERM while waiting to open a scene FIFO: status 130", "[hostile]") {
  TempDir dir;
  const std::string fifo = dir / "scene.toml";
  REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
  Process process({"solve", fifo});
  REQUIRE(process.wait_for_fifo_open());
  process.signal(SIGTERM);
  const Result r = process.wait(std::chrono::seconds(20));
  CHECK(r.status == 130);
  CHECK_THAT(r.err, Catch::Contains(fifo + ": interrupted by SIGTERM while opening or reading"));
}

TEST_CASE("solve --reference on an unbounded scene: status 4 and the result file", "[hostile]") {
  TempDir dir;
  const std::string scene = dir / "unbounded.toml";
  {
    std::ofstream(scene) << fetic::testing::SceneToml("bar", "[defaults]",
                                                      "E = 2.1e11, area = 1e-4, elements = 2")
                                .strut("L", {0.0, 0.0}, {1.0, 0.0}, "fixed = ['from']")
                                .strut("R", {1.001, 0.0}, {2.0, 0.0})
                                .load("R", "to", {1000.0, 0.0})
                                .contact("L.to", "R.from")
                                .str();
  }
  const std::string json = dir / "r.json";
  const Result r = run_fetic({"solve", scene, "--reference", "--json", json});
  INFO(r.err);
  CHECK(r.status == 4);
  CHECK_THAT(r.err, Catch::Contains("the scene is unbounded"));
  CHECK(nlohmann::json::parse(read_text(json))["converged"] == false);
}

TEST_CASE("generate refuses scenes beyond the limits at once, and stops on SIGINT", "[hostile]") {
  const auto start = std::chrono::steady_clock::now();
  const Result unknowns = run_fetic({"generate", "--pairs", "1000000"});
  CHECK(unknowns.status == 1);
  CHECK_THAT(unknowns.err, Catch::Contains("the scene would have 1188000000 unknowns, more "
                                           "than the limit of 20000000"));
  const Result text = run_fetic(
      {"generate", "--pairs", "1000000", "--model", "bar", "--elements", "4", "--subdomains", "1"});
  CHECK(text.status == 1);
  CHECK_THAT(text.err, Catch::Contains("MiB of TOML, more than the 64 MiB a scene file may have"));
  // The product of the counts would overflow 64-bit integers.
  const Result huge = run_fetic({"generate", "--elements", "1000000000,1000000000"});
  CHECK(huge.status == 1);
  CHECK_THAT(huge.err, Catch::Contains("the scene would have 40000000"));
  // Counts generate_scene() cannot use, named by option and value.
  const Result zero = run_fetic({"generate", "--elements", "3,0"});
  CHECK(zero.status == 1);
  CHECK_THAT(zero.err, Catch::Contains("--elements 3,0: the counts must be whole numbers"));
  const Result split = run_fetic({"generate", "--subdomains", "33,1"});
  CHECK(split.status == 1);
  CHECK_THAT(split.err, Catch::Contains("--subdomains 33,1: 33 subdomains along a strut of 32 "
                                        "elements; each subdomain needs an element"));
  CHECK(std::chrono::steady_clock::now() - start < std::chrono::seconds(20));

  TempDir dir;
  const std::string out = dir / "big.toml";
  Process process({"generate", "--pairs", "130000", "--model", "bar", "--elements", "1",
                   "--subdomains", "1", "-o", out});
  REQUIRE(process.wait_for_signal_handlers());
  std::this_thread::sleep_for(std::chrono::milliseconds(200));  // generating by now
  process.signal(SIGINT);
  const Result r = process.wait(std::chrono::seconds(60));
  CHECK(r.status == 130);
  CHECK_THAT(r.err, Catch::Contains("interrupted by SIGINT; no scene written"));
  CHECK(fs::is_empty(dir.path()));  // neither the scene nor a temporary file
}
