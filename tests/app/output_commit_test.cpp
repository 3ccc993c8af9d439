// Every output is checked before the work starts and committed only when all outputs of
// the run can be written (app/output_file.hpp, PendingOutputs): an existing file is never
// replaced by a run that then fails; an option that would write nothing is refused.

#include <catch2/catch.hpp>

#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "tests/support/process.hpp"

using namespace fetic::test;
namespace fs = std::filesystem;

namespace {

const std::string kScene = bundled_scene("two_bars.toml");

void write_text(const std::string& path, const std::string& text) {
  std::ofstream(path) << text;
}

// No NAME.tmpPID or other file beside the ones named.
std::vector<std::string> names_in(const std::string& folder) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(folder))
    names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

}  // namespace

TEST_CASE("a missing folder for one output: refused before the solve, the others kept",
          "[output]") {
  TempDir dir;
  const std::string keep = dir / "KEEP.json";
  write_text(keep, "old");
  const Result r = run_fetic({"solve", kScene, "--json", keep, "--csv", dir / "nodir/x.csv"});
  CHECK(r.status == 5);
  CHECK_THAT(r.err, Catch::Contains("nodir") && Catch::Contains("does not exist"));
  CHECK_THAT(r.out, !Catch::Contains("converged"));  // refused before the solve
  CHECK(read_text(keep) == "old");
  CHECK(names_in(dir.path()) == std::vector<std::string>{"KEEP.json"});
}

TEST_CASE("every kind of bad target is refused before the work, naming it", "[output]") {
  TempDir dir;
  fs::create_directories(dir / "folder");
  write_text(dir / "file", "x");
  const std::string keep = dir / "keep.json";
  write_text(keep, "old");
  fs::create_symlink(dir / "missing/target.json", dir / "dangling");
  fs::create_symlink(dir / "missing_folder", dir / "dangling_folder");
  struct Case {
    std::vector<std::string> options;
    std::string message;
  };
  for (const Case& c : std::vector<Case>{
           {{"--csv", dir / "folder"}, "is a directory"},
           {{"--csv-steps", dir / "file/x.csv"}, "is a file, not a folder"},
           {{"--monitor", dir / "dangling"}, "that the symbolic link points into does not exist"},
           {{"--profile", dir / "nodir/p.json", "--method", "feti"}, "does not exist"},
           {{"--vtu", dir / "file"}, "is a file, not a folder"},
           {{"--vtu", dir / "file/sub"}, "is a file, not a folder"},
           {{"--vtu", dir / "dangling_folder"}, "which does not exist; give the name of a folder"},
       }) {
    std::vector<std::string> command{"solve", kScene, "--json", keep};
    command.insert(command.end(), c.options.begin(), c.options.end());
    INFO(c.options[0] << " " << c.options[1]);
    const Result r = run_fetic(command);
    CHECK(r.status == 5);
    CHECK_THAT(r.err, Catch::Contains(c.message));
    CHECK(read_text(keep) == "old");
  }
  CHECK_FALSE(fs::exists(dir / "missing_folder"));
}

TEST_CASE("an output that fails during the run leaves every existing output alone", "[output]") {
  if (!can_make_devices()) {
    WARN("skipped: mknod needs root");
    return;
  }
  TempDir dir;
  const std::string full = make_char_device(dir, "full", 1, 7);
  const std::string json = dir / "r.json", csv = dir / "r.csv", vtu = dir / "vtu";
  write_text(json, "old json");
  write_text(csv, "old csv");
  fs::create_directories(vtu);
  write_text(vtu + "/struts.pvd", "old pvd");
  // The monitor's lines are lost on the full device: the run fails (5), nothing replaced.
  const Result r =
      run_fetic({"solve", kScene, "--json", json, "--csv", csv, "--vtu", vtu, "--monitor", full});
  CHECK(r.status == 5);
  CHECK_THAT(r.err, Catch::Contains(full) && Catch::Contains("No space left on device"));
  CHECK(read_text(json) == "old json");
  CHECK(read_text(csv) == "old csv");
  CHECK(read_text(vtu + "/struts.pvd") == "old pvd");
  CHECK(names_in(vtu) == std::vector<std::string>{"struts.pvd"});  // no temporary left
  CHECK(names_in(dir.path()) == (std::vector<std::string>{"full", "r.csv", "r.json", "vtu"}));
}

TEST_CASE("a run that succeeds replaces every output, the monitor included", "[output]") {
  TempDir dir;
  const std::string json = dir / "r.json", monitor = dir / "m.jsonl", vtu = dir / "vtu";
  write_text(json, "old");
  write_text(monitor, "old");
  const Result r = run_fetic({"solve", kScene, "--json", json, "--monitor", monitor, "--vtu", vtu,
                              "--csv", dir / "r.csv"});
  INFO(r.err);
  REQUIRE(r.status == 0);
  CHECK(nlohmann::json::parse(read_text(json))["converged"] == true);
  // The new monitor: its header line (version, units), then the iterations.
  const std::string lines = read_text(monitor);
  CHECK_THAT(lines, Catch::StartsWith("{\"fetic_version\""));
  CHECK_THAT(lines, Catch::Contains("\n{\"load_factor\""));
  CHECK(fs::exists(vtu + "/struts.pvd"));
  CHECK(names_in(dir.path()) == (std::vector<std::string>{"m.jsonl", "r.csv", "r.json", "vtu"}));
}

TEST_CASE("an option that would write nothing is refused with status 1", "[output]") {
  for (const std::vector<std::string>& options : {std::vector<std::string>{"--json", ""},
                                                  {"--csv", ""},
                                                  {"--csv-steps", ""},
                                                  {"--monitor", ""},
                                                  {"--profile", ""},
                                                  {"--vtu", ""}}) {
    INFO(options[0]);
    std::vector<std::string> command{"solve", kScene};
    command.insert(command.end(), options.begin(), options.end());
    const Result r = run_fetic(command);
    CHECK(r.status == 1);
    CHECK_THAT(r.err, Catch::Contains(options[0]) && Catch::Contains("an empty name"));
  }
  for (const std::vector<std::string>& command :
       {std::vector<std::string>{"render", kScene, "--out", ""},
        {"render", kScene, "--movie", ""},
        {"render", kScene, "--final", "--out", "x", "--vtu", ""},
        {"generate", "--pairs", "2", "-o", ""},
        {"bench", kScene, "--csv", ""}}) {
    INFO(command[0] << " " << command[command.size() - 2]);
    const Result r = run_fetic(command);
    CHECK(r.status == 1);
    CHECK_THAT(r.err, Catch::Contains("an empty name writes nothing"));
  }
  // --profile for a method that keeps none.
  for (const char* method : {"active-set", "cg", "sd"}) {
    TempDir dir;
    const Result r = run_fetic({"solve", kScene, "--method", method, "--profile", dir / "p.json"});
    CHECK(r.status == 1);
    CHECK_THAT(r.err, Catch::Contains("keeps no profile"));
    CHECK_FALSE(fs::exists(dir / "p.json"));
  }
}
