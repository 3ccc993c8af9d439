// Messages quote values shortened and escaped (scenes/message_text.hpp) and name the
// range wherever one applies (issue 27, item 9).

#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <regex>
#include <string>

#include "tests/support/process.hpp"

using namespace fetic::test;

namespace {

const std::string kScene = bundled_scene("two_bars.toml");

// The longest line of a message.
size_t longest_line(const std::string& text) {
  size_t longest = 0, start = 0;
  for (size_t end; (end = text.find('\n', start)) != std::string::npos; start = end + 1)
    longest = std::max(longest, end - start);
  return std::max(longest, text.size() - start);
}

}  // namespace

TEST_CASE("the option --monitor-full names its range, never CLI11's 309 digits", "[messages]") {
  for (const char* value : {"0", "1e12", "-3", "x"}) {
    INFO(value);
    const Result r = run_fetic({"solve", kScene, "--monitor", "-", "--monitor-full", value});
    CHECK(r.status == 1);
    CHECK_THAT(r.err, Catch::Contains("--monitor-full") &&
                          Catch::Contains("must be a whole number from 1 to 1000000000"));
    CHECK(longest_line(r.err) < 200);
  }
}

TEST_CASE("a long value is quoted cut, with its length", "[messages]") {
  const std::string huge(100000, '7');
  const Result r = run_fetic({"solve", kScene, "--tol", huge});
  CHECK(r.status == 1);
  CHECK_THAT(r.err, Catch::Contains("... (100000 bytes)"));
  CHECK(longest_line(r.err) < 200);

  // A scene whose unknown key is 1 MB long: one short line naming the file and the line.
  TempDir dir;
  const std::string scene = dir / "long_key.toml";
  std::ofstream(scene) << read_text(kScene) << std::string(1 << 20, 'k') << " = 1\n";
  const Result loaded = run_fetic({"solve", scene});
  CHECK(loaded.status == 2);
  CHECK_THAT(loaded.err,
             Catch::Contains("unknown key 'kkkk") && Catch::Contains("(1048576 bytes)"));
  CHECK(longest_line(loaded.err) < 400);
}

TEST_CASE("a node index beyond an int is out of range, not 'not a number'", "[messages]") {
  TempDir dir;
  const Result r = run_fetic({"solve", kScene, "--csv-steps", dir / "s.csv", "--csv-node",
                              "left@123456789012345678901234567890"});
  CHECK(r.status == 1);
  CHECK_THAT(r.err, Catch::Contains("node index 123456789012345678901234567890 is out of range") &&
                        Catch::Contains("has nodes 0..4"));
}

TEST_CASE("a frame strut singular by its inertia is told to check inertia", "[messages]") {
  TempDir dir;
  std::string text = read_text(bundled_scene("frame_post_on_beam.toml"));
  text = std::regex_replace(text, std::regex("inertia = 2.0e-7"), "inertia = 1.0e-30");
  const std::string scene = dir / "thin_post.toml";
  std::ofstream(scene) << text;
  const Result r = run_fetic({"solve", scene, "--method", "feti-c"});
  INFO(r.err);
  CHECK(r.status == 3);
  CHECK_THAT(r.err, Catch::Contains("strut 'post'") && Catch::Contains("check inertia"));
}
