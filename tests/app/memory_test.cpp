// Memory: a scene that needs more than the process may have is refused before the work
// with the estimate and the limit (status 7); an allocation that fails anyway is
// "out of memory while ...", status 7, never an abort. The limit is the child's own
// address-space limit (ulimit -v), so the test never touches the machine's memory.

#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/memory_estimate.hpp"
#include "scenes/load_scene.hpp"
#include "tests/support/process.hpp"
#include "tests/support/skip.hpp"

using namespace fetic::test;
namespace fs = std::filesystem;

// AddressSanitizer reserves terabytes of address space for its shadow memory: under
// scripts/sanitize.sh no ulimit -v would let the program start, so these tests skip.
#ifdef __SANITIZE_ADDRESS__
#define SKIP_UNDER_ASAN() FETIC_SKIP("ulimit -v cannot limit a program built with ASan")
#else
#define SKIP_UNDER_ASAN() \
  do {                    \
  } while (false)
#endif

namespace {

// About 500 MB of FETI-C: 4,000 bar struts in 40,000 subdomains.
std::string large_scene(const TempDir& dir) {
  const std::string path = dir / "large.toml";
  const Result r = run_fetic({"generate", "--model", "bar", "--pairs", "2000", "--elements", "100",
                              "--subdomains", "10", "-o", path});
  REQUIRE(r.status == 0);
  return path;
}

Streams limited(const std::string& kilobytes, bool check = true) {
  Streams streams;
  streams.shell_prefix = "ulimit -v " + kilobytes;
  if (!check) streams.environment.push_back("FETIC_MEMORY_CHECK=off");
  return streams;
}

}  // namespace

TEST_CASE("a scene too large for the memory limit is refused before assembly, by every command",
          "[memory]") {
  SKIP_UNDER_ASAN();
  TempDir dir;
  const std::string scene = large_scene(dir);
  for (const std::vector<std::string>& command : {std::vector<std::string>{"solve", scene},
                                                  {"bench", scene, "--repeat", "1"},
                                                  {"render", scene, "--out", dir / "frames"},
                                                  {"gui", scene}}) {
    INFO(command[0]);
    const auto start = std::chrono::steady_clock::now();
    const Result r = run_fetic(command, limited("300000"));
    CHECK(r.status == 7);
    CHECK_THAT(r.err, Catch::Contains(scene + ": not enough memory: ") &&
                          Catch::Contains("(404000 unknowns, 4000 struts, 40000 subdomains, "
                                          "2000 contacts) needs about") &&
                          Catch::Contains("is available (the address-space limit (ulimit -v))"));
    CHECK(std::chrono::steady_clock::now() - start < std::chrono::seconds(30));
  }
  CHECK_FALSE(fs::exists(dir / "frames"));
  // Unlimited, the same scene solves.
  CHECK(run_fetic({"solve", scene, "--quiet", "--max-iterations", "3"}).status == 4);
}

TEST_CASE("std::bad_alloc while working is 'out of memory while ...', status 7", "[memory]") {
  SKIP_UNDER_ASAN();
  TempDir dir;
  const std::string scene = large_scene(dir);
  const std::string json = dir / "r.json";
  const Result r = run_fetic({"solve", scene, "--json", json}, limited("300000", false));
  INFO(r.err);
  CHECK(r.signal == 0);  // no abort
  CHECK(r.status == 7);
  CHECK_THAT(r.err, Catch::StartsWith("fetic: out of memory while "));
  CHECK_FALSE(fs::exists(json));
}

TEST_CASE("a scene file whose parsing would not fit is refused before reading", "[memory]") {
  SKIP_UNDER_ASAN();
  TempDir dir;
  const std::string scene = dir / "large.toml";
  { std::ofstream(scene) << "model = \"bar\"\n"; }
  fs::resize_file(scene, 60 << 20);  // sparse: its size is what counts
  const Result r = run_fetic({"solve", scene}, limited("300000"));
  CHECK(r.status == 7);
  CHECK_THAT(r.err, Catch::Contains("not enough memory: reading this scene file (63 MB) needs "
                                    "about 1.0 GB"));
  // Without the check the parser runs out of memory, and says so.
  const Result unchecked = run_fetic({"solve", scene}, limited("300000", false));
  CHECK(unchecked.signal == 0);
  CHECK((unchecked.status == 7 || unchecked.status == 2));  // 2: the NUL bytes, if it fits
}

TEST_CASE("generate refuses a scene it could not check within the memory limit", "[memory]") {
  SKIP_UNDER_ASAN();
  const Result r = run_fetic({"generate", "--model", "bar", "--pairs", "130000", "--elements", "1",
                              "--subdomains", "1", "-o", "/nonexistent/never"},
                             limited("300000"));
  CHECK(r.status == 7);
  CHECK_THAT(r.err, Catch::Contains("fetic generate: not enough memory: making and checking a "
                                    "scene of about"));
}

TEST_CASE("the memory estimate is within 25% of the measured peak on bar, plane and frame scenes",
          "[memory]") {
  // The memory check's model (app/memory_estimate.cpp) against the peak resident memory
  // the run itself reports (--profile: getrusage's maximum resident set), one dual method
  // per model and the output options, on scenes of about 1e5 unknowns. ASan's shadow
  // memory would be counted in the peak.
#ifdef __SANITIZE_ADDRESS__
  FETIC_SKIP("the peak of a program built with ASan includes its shadow memory");
#endif
  struct Case {
    std::vector<std::string> generate;
    std::string method;
    bool outputs;
  };
  const std::vector<Case> cases = {
      {{"--model", "bar", "--pairs", "50", "--elements", "1000", "--subdomains", "10"},
       "mprgp",
       true},
      {{"--model", "plane", "--pairs", "5", "--elements", "200,24", "--subdomains", "10,1"},
       "feti-c",
       false},
      {{"--model", "frame", "--pairs", "5", "--elements", "1000", "--subdomains", "10"},
       "feti-dp",
       true}};
  TempDir dir;
  for (const Case& c : cases) {
    const std::string scene = dir / "scene.toml", profile = dir / "profile.json";
    std::vector<std::string> generate = {"generate", "-o", scene};
    generate.insert(generate.end(), c.generate.begin(), c.generate.end());
    REQUIRE(run_fetic(generate).status == 0);
    std::vector<std::string> solve = {"solve",     scene,   "--method", c.method,
                                      "--profile", profile, "--quiet"};
    if (c.outputs) solve.insert(solve.end(), {"--json", dir / "r.json", "--vtu", dir / "vtu"});
    const Result r = run_fetic(solve);
    INFO(c.generate[1] << " " << c.method << "\n" << r.err);
    REQUIRE(r.status == 0);
    std::ifstream in(profile);
    const nlohmann::json p = nlohmann::json::parse(in);
    const double estimated = p.at("estimated_peak_bytes");
    const double measured = p.at("processes").at(0).at("peak_resident_bytes");
    INFO("estimated " << estimated / 1e6 << " MB, measured " << measured / 1e6 << " MB");
    CHECK(estimated > 0.75 * measured);
    CHECK(estimated < 1.25 * measured);
  }
}

// The window keeps a solve's iterates thinned to a byte budget (app/gui/iterate_store.hpp):
// its memory check counts at most that budget, but never fewer than the three iterates the
// store always keeps, so that a large scene is not refused for 100 iterates it never holds.
TEST_CASE("the window's kept iterates count at most their budget, and at least three", "[memory]") {
  const fetic::scenes::Scene scene =
      fetic::scenes::load_scene_file(std::string(FETIC_BUNDLED_SCENES_DIR) + "/plane_pair.toml");
  fetic::app::MemoryUse use;
  use.methods = {fetic::solver::MethodKind::Mprgp};
  const double solve = fetic::app::estimate_memory(scene, use).bytes;
  use.kept_iterates = 1;
  const double iterate = fetic::app::estimate_memory(scene, use).bytes - solve;
  REQUIRE(iterate > 0.0);
  use.kept_iterates = 100;
  CHECK(fetic::app::estimate_memory(scene, use).bytes == Approx(solve + 100 * iterate));
  use.kept_iterate_budget = 10.5 * iterate;
  CHECK(fetic::app::estimate_memory(scene, use).bytes == Approx(solve + 10.5 * iterate));
  use.kept_iterate_budget = 0.5 * iterate;  // below three iterates: three count
  CHECK(fetic::app::estimate_memory(scene, use).bytes == Approx(solve + 3 * iterate));
}
