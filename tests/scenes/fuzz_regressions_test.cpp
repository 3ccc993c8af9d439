// Inputs that once crashed fuzz/fuzz_scene (scripts/fuzz.sh), kept as regression tests:
// each must load as a valid scene (which loads again after scene_to_toml()) or be refused
// with a SceneError whose every line names the file, the same invariants as the fuzz
// target. NAME.expect, when present, holds text the message must contain. Inputs that
// start with "#!repeat N" are expanded first, as the fuzz target does
// (fuzz/expand_repeats.hpp).

#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "fuzz/expand_repeats.hpp"
#include "scenes/load_scene.hpp"
#include "scenes/write_scene.hpp"

namespace {

std::string read_bytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

}  // namespace

TEST_CASE("inputs that crashed the fuzzer are refused cleanly, naming the file") {
  int files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(FETIC_FUZZ_REGRESSIONS_DIR)) {
    if (entry.path().extension() != ".toml") continue;
    ++files;
    const std::string path = entry.path().string();
    INFO(path);
    std::filesystem::path expect_file = entry.path();
    expect_file.replace_extension(".expect");
    const std::string expected =
        std::filesystem::exists(expect_file) ? read_bytes(expect_file) : std::string();
    try {
      const fetic::scenes::Scene scene =
          fetic::scenes::parse_scene(fetic::fuzz::expand_repeats(read_bytes(path)), path);
      CHECK(expected.empty());  // an expected message means the input must be refused
      CHECK(scene.path == path);
      // and, as in the fuzz target, it survives a round trip through scene_to_toml()
      const std::string text = fetic::scenes::scene_to_toml(scene);
      INFO(text);
      const fetic::scenes::Scene again = fetic::scenes::parse_scene(text, path);
      CHECK(again.title == scene.title);
      CHECK(again.struts.size() == scene.struts.size());
    } catch (const fetic::scenes::SceneError& error) {
      const std::string message = error.what();
      INFO(message);
      CHECK_FALSE(error.problems().empty());
      size_t start = 0;
      while (start <= message.size()) {
        const size_t end = std::min(message.find('\n', start), message.size());
        CHECK(message.compare(start, path.size() + 1, path + ":") == 0);
        start = end + 1;
      }
      if (!expected.empty()) CHECK_THAT(message, Catch::Contains(expected));
    }
  }
  CHECK(files >= 1);
}
