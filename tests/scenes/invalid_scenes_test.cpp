// Every invalid scene in tests/scenes/invalid is rejected with the message its header
// states, naming the file and the line:
//   # expect-line: 12        (or "none" when the problem has no line)
//   # expect: text the message must contain

#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <string>

#include "scenes/load_scene.hpp"

namespace {

struct Expectation {
  std::string line;  // "none" or a number
  std::string text;
};

Expectation read_expectation(const std::filesystem::path& path) {
  std::ifstream file(path);
  Expectation e;
  std::string line;
  while (std::getline(file, line)) {
    if (line.rfind("# expect-line: ", 0) == 0) e.line = line.substr(15);
    if (line.rfind("# expect: ", 0) == 0) e.text = line.substr(10);
  }
  return e;
}

}  // namespace

TEST_CASE("each invalid scene is rejected with its expected message, file and line") {
  int files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(FETIC_INVALID_SCENES_DIR)) {
    if (entry.path().extension() != ".toml") continue;
    ++files;
    const std::string path = entry.path().string();
    const Expectation expected = read_expectation(entry.path());
    INFO(path);
    REQUIRE_FALSE(expected.text.empty());
    REQUIRE_FALSE(expected.line.empty());
    try {
      fetic::scenes::load_scene_file(path);
      FAIL("the scene was accepted");
    } catch (const fetic::scenes::SceneError& error) {
      const std::string message = error.what();
      INFO(message);
      const std::string prefix =
          expected.line == "none" ? path + ": " : path + ":" + expected.line + ": ";
      // The expected problem is reported at its line, with its text, on one line.
      bool found = false;
      size_t start = 0;
      while (start <= message.size()) {
        const size_t end = std::min(message.find('\n', start), message.size());
        const std::string one = message.substr(start, end - start);
        if (one.rfind(prefix, 0) == 0 && one.find(expected.text) != std::string::npos) found = true;
        start = end + 1;
      }
      CHECK(found);
    }
  }
  CHECK(files >= 50);
}

TEST_CASE("a missing scene file is reported with its path") {
  try {
    fetic::scenes::load_scene_file("no/such/scene.toml");
    FAIL("accepted");
  } catch (const fetic::scenes::SceneError& error) {
    CHECK(std::string(error.what()) ==
          "no/such/scene.toml: cannot open the scene file (No such file or directory)");
  }
}

TEST_CASE("several problems in one file are all reported") {
  const char* text = R"(model = "bar"
[[strut]]
name = "A"
from = [0.0, 0.0]
to = [1.0, 0.0]
E = -1
area = 0
elements = 2
fixed = ["from"]
)";
  try {
    fetic::scenes::parse_scene(text, "two.toml");
    FAIL("accepted");
  } catch (const fetic::scenes::SceneError& error) {
    CHECK(error.problems().size() == 2);
    CHECK_THAT(error.what(),
               Catch::Contains("two.toml:6: strut 'A': 'E' must be greater than 0") &&
                   Catch::Contains("two.toml:7: strut 'A': 'area' must be greater than 0"));
  }
}
