// The command line itself: bundled scenes by name from any directory (and where fetic
// looked when it finds none), `fetic scenes`, `fetic help`, `-v`, "did you mean" for an
// unknown option, the version in every output, and the exit statuses each help lists.

#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <string>

#include <nlohmann/json.hpp>

#include "tests/support/process.hpp"
#include "tests/support/shell_run.hpp"

namespace {

namespace fs = std::filesystem;
using fetic::test::read_text;
using fetic::test::TempDir;
using nlohmann::json;

// fetic run from `directory` (not the source or build tree).
fetic::test::ShellRun run_in(const TempDir& directory, const std::string& arguments) {
  return fetic::test::run_shell("cd '" + directory.path().string() +
                                "' && env -u FETIC_DATA_DIR '" + FETIC_EXECUTABLE + "' " +
                                arguments);
}

std::string bundled(const std::string& name) {
  return fs::canonical(fs::path(FETIC_BUNDLED_SCENES_DIR) / name).string();
}

// The title line of a scene file, read as text (not by fetic's loader).
std::string title_in_file(const fs::path& file) {
  std::ifstream in(file);
  const std::regex title(R"re(^title\s*=\s*"(.*)"\s*$)re");
  std::smatch match;
  for (std::string line; std::getline(in, line);)
    if (std::regex_match(line, match, title)) return match[1];
  return "";
}

}  // namespace

TEST_CASE("a bundled scene is found by name from any directory") {
  TempDir here;
  for (const std::string name : {"two_bars", "two_bars.toml", "scenes/two_bars.toml"}) {
    INFO(name);
    const auto run = run_in(here, "solve " + name + " --quiet --json r.json");
    INFO(run.output);
    REQUIRE(run.status == 0);
    const json result = json::parse(read_text(here / "r.json"));
    CHECK(fs::canonical(result["scene"].get<std::string>()).string() == bundled("two_bars.toml"));
  }
}

TEST_CASE("a scene file in the working directory wins over a bundled scene of the name") {
  TempDir here;
  std::string text = read_text(bundled("two_bars.toml"));
  text = std::regex_replace(text, std::regex(R"(title = "[^"]*")"), R"(title = "my own copy")");
  std::ofstream(here / "two_bars.toml") << text;
  const auto run = run_in(here, "solve two_bars.toml --quiet --json r.json");
  INFO(run.output);
  REQUIRE(run.status == 0);
  CHECK(json::parse(read_text(here / "r.json"))["title"] == "my own copy");
}

TEST_CASE("a scene found nowhere: status 2 and every place fetic looked") {
  TempDir here;
  const auto run = run_in(here, "solve no_such_scene --quiet");
  INFO(run.output);
  CHECK(run.status == 2);
  CHECK_THAT(run.output, Catch::Contains("cannot open the scene file"));
  CHECK_THAT(run.output, Catch::Contains("looked in:"));
  CHECK_THAT(run.output, Catch::Contains((here.path() / "no_such_scene").string()));
  const std::string folder = fs::canonical(FETIC_BUNDLED_SCENES_DIR).string();
  CHECK_THAT(run.output, Catch::Contains(folder + "/no_such_scene.toml"));
  CHECK_THAT(run.output, Catch::Contains("fetic scenes"));
}

TEST_CASE("fetic scenes lists every bundled scene with its title") {
  TempDir here;
  const auto run = run_in(here, "scenes");
  INFO(run.output);
  REQUIRE(run.status == 0);
  int count = 0;
  for (const auto& entry : fs::directory_iterator(FETIC_BUNDLED_SCENES_DIR)) {
    if (entry.path().extension() != ".toml") continue;
    ++count;
    const std::string title = title_in_file(entry.path());
    INFO(entry.path());
    REQUIRE_FALSE(title.empty());
    const std::regex line(
        "\n  " + entry.path().stem().string() + " +" +
        std::regex_replace(title, std::regex(R"([.^$|()\[\]{}*+?\\])"), R"(\$&)") + "\n");
    CHECK(std::regex_search(run.output, line));
  }
  CHECK(count >= 10);
}

TEST_CASE("an unknown option gets a suggestion") {
  TempDir here;
  const auto run = run_in(here, "solve two_bars --methd feti-c");
  INFO(run.output);
  CHECK(run.status == 1);
  CHECK_THAT(run.output, Catch::Contains("unknown option '--methd'; did you mean '--method'?"));
  const auto render = run_in(here, "render two_bars --magnificaton 2");
  CHECK(render.status == 1);
  CHECK_THAT(render.output, Catch::Contains("did you mean '--magnification'?"));
  // Nothing near: no suggestion, still named.
  const auto far = run_in(here, "solve two_bars --zzzzzzzzzz");
  CHECK(far.status == 1);
  CHECK_THAT(far.output, Catch::Contains("unknown option '--zzzzzzzzzz'"));
  CHECK_THAT(far.output, !Catch::Contains("did you mean"));
}

TEST_CASE("fetic help [COMMAND] and fetic -v") {
  TempDir here;
  const auto help = run_in(here, "help solve"), direct = run_in(here, "solve --help");
  CHECK(help.status == 0);
  CHECK(help.output == direct.output);
  CHECK_THAT(help.output, Catch::Contains("--method"));
  const auto program = run_in(here, "help");
  CHECK(program.status == 0);
  CHECK_THAT(program.output, Catch::Contains("scenes"));
  CHECK(run_in(here, "help nosuch").status == 1);
  const auto v = run_in(here, "-v"), version = run_in(here, "--version");
  CHECK(v.status == 0);
  CHECK(v.output == version.output);
  CHECK_THAT(v.output, Catch::Contains(FETIC_VERSION));
}

TEST_CASE("the result file and the ParaView files say which version wrote them") {
  TempDir here;
  const auto run = run_in(here, "solve two_bars --quiet --json r.json --vtu vtu");
  INFO(run.output);
  REQUIRE(run.status == 0);
  CHECK(json::parse(read_text(here / "r.json"))["fetic_version"] == FETIC_VERSION);
  // A VTK String array: the character codes, then 0.
  std::string codes;
  for (char c : std::string(FETIC_VERSION))
    codes += std::to_string(static_cast<int>(c)) + " ";
  for (const char* file : {"vtu/struts_0000.vtu", "vtu/contacts_0000.vtu"}) {
    INFO(file);
    const std::string text = read_text(here / file);
    const auto at = text.find("Name=\"fetic_version\"");
    REQUIRE(at != std::string::npos);
    CHECK(text.find(codes + "0", at) != std::string::npos);
  }
}

TEST_CASE("every command's help lists every status it can return") {
  // From the code: 1 (command line), 5 (stdout not writable) and 7 (out of memory) for
  // every command; the rest per command.
  const std::map<std::string, std::set<int>> statuses = {
      {"solve", {0, 1, 2, 3, 4, 5, 7, 130}},
      {"render", {0, 1, 2, 3, 4, 5, 6, 7, 130}},
      {"gui", {0, 1, 2, 3, 4, 5, 6, 7, 130}},
      {"figures", {0, 1, 2, 3, 5, 6, 7, 130}},
      {"bench", {0, 1, 2, 3, 5, 7, 130}},
      {"bench-render", {0, 1, 2, 3, 5, 6, 7, 130}},
      {"generate", {0, 1, 5, 7, 130}},
      {"scenes", {0, 1, 2, 5}},
      {"help", {0, 1, 5}}};
  TempDir here;
  for (const auto& [command, codes] : statuses) {
    const auto run = run_in(here, command + " --help");
    INFO(command << "\n" << run.output);
    REQUIRE(run.status == 0);
    const auto at = run.output.find("Exit status:\n");
    REQUIRE(at != std::string::npos);
    std::set<int> listed;
    const std::regex entry(R"(\n  (\d+) +\S)");
    for (std::sregex_iterator
             it(run.output.begin() + static_cast<long>(at), run.output.end(), entry),
         end;
         it != end; ++it)
      listed.insert(std::stoi((*it)[1]));
    CHECK(listed == codes);
  }
}
