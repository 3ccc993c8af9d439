// The limits checked before toml++ sees a scene (scenes/toml_guard.hpp, scene_text.hpp): nesting of
// every kind toml++ recurses on, the file size (checked before reading), streams read only up to
// the limit, directories refused. Inputs are made here, in private temporary folders.

#include <catch2/catch.hpp>

#include <fcntl.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <unistd.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>

#include "scenes/load_scene.hpp"
#include "scenes/scene_text.hpp"
#include "scenes/toml_guard.hpp"
#include "tests/support/skip.hpp"

using namespace fetic::scenes;
namespace fs = std::filesystem;

namespace {

std::string repeat(const std::string& piece, int count) {
  std::string text;
  for (int i = 0; i < count; ++i)
    text += piece;
  return text;
}

const std::string kHead = "model = \"bar\"\n";

// Every shape of nesting, `levels` deep.
std::vector<std::pair<std::string, std::string>> nested(int levels) {
  return {
      {"dotted key", kHead + repeat("a.", levels - 1) + "a = 1\n"},
      {"quoted dotted key", kHead + repeat("\"a\" . ", levels - 1) + "'a' = 1\n"},
      {"table header", kHead + "[" + repeat("a.", levels - 1) + "a]\n"},
      {"array-of-tables header", kHead + "[[" + repeat("a.", levels - 1) + "a]]\n"},
      {"array", kHead + "a = " + repeat("[", levels) + repeat("]", levels) + "\n"},
      {"inline table",
       kHead + "a = " + repeat("{a = ", levels - 1) + "{}" + repeat("}", levels - 1) + "\n"},
      {"inline table with dotted keys",
       kHead + "a = " + repeat("{b.c = ", levels / 2) + "1" + repeat("}", levels / 2) + "\n"},
      {"arrays of inline tables",
       kHead + "a = " + repeat("[{a = ", levels / 2) + "1" + repeat("}]", levels / 2) + "\n"},
      {"header, then a dotted key",
       kHead + "[" + repeat("h.", levels / 4) + "h]\n" + repeat("k.", levels / 2) + "k = 1\n"},
  };
}

}  // namespace

TEST_CASE("nesting of every kind is refused beyond the limit, before toml++ parses it") {
  for (const auto& [shape, text] : nested(kMaxNesting + 2)) {
    INFO(shape << "\n" << text);
    const Problem problem = toml_guard_problem(text);
    CHECK(problem.line == (shape == "header, then a dotted key" ? 3 : 2));
    CHECK_THAT(problem.message, Catch::Contains("nests deeper than 32 levels"));
  }
  // Shallow versions are left to the TOML parser and the scene checks.
  for (const auto& [shape, text] : nested(6)) {
    INFO(shape << "\n" << text);
    CHECK(toml_guard_problem(text).line == 0);
  }
}

TEST_CASE("a scene nested 100,000 deep is an error with file and line, not a crash") {
  for (const auto& [shape, text] : nested(100000)) {
    INFO(shape);
    try {
      parse_scene(text, "deep.toml");
      FAIL("accepted");
    } catch (const SceneError& error) {
      CHECK_THAT(error.what(), Catch::StartsWith("deep.toml:") &&
                                   Catch::Contains(": the TOML nests deeper than 32 levels"));
    }
  }
}

TEST_CASE("strings and comments do not count as nesting, valid scenes pass") {
  const std::string text = kHead + "title = \"[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[a.b.c\"\n" +
                           "# " + repeat("[{a.", 100) + "\n" + "x = '''\n" + repeat("[", 100) +
                           "\n'''\n" + "y = \"\"\"" + repeat("{\\\"", 50) + "\"\"\"\n";
  CHECK(toml_guard_problem(text).line == 0);
  for (const auto& entry : fs::directory_iterator(FETIC_BUNDLED_SCENES_DIR)) {
    if (entry.path().extension() != ".toml") continue;
    std::ifstream in(entry.path());
    const std::string scene{std::istreambuf_iterator<char>(in), {}};
    INFO(entry.path());
    CHECK(toml_guard_problem(scene).line == 0);
  }
  // A scene written inline, at the depth a scene needs.
  const std::string inline_scene =
      kHead +
      "strut = [{name = \"a\", from = [0, 0], to = [1, 0], E = 1e9, area = 1e-4, elements = 2, "
      "fixed = [\"from\"]}]\n";
  CHECK(toml_guard_problem(inline_scene).line == 0);
  CHECK(parse_scene(inline_scene, "inline.toml").struts.size() == 1);
}

namespace {

struct TempDir {
  fs::path path = fs::temp_directory_path() / ("fetic_scene_text_" + std::to_string(::getpid()));
  TempDir() {
    fs::remove_all(path);
    fs::create_directories(path);
  }
  ~TempDir() {
    std::error_code ignored;
    fs::remove_all(path, ignored);
  }
  std::string operator/(const std::string& name) const { return (path / name).string(); }
};

std::string load_error(const std::string& path) {
  try {
    load_scene_file(path);
  } catch (const SceneError& error) {
    return error.what();
  }
  return "(loaded)";
}

}  // namespace

TEST_CASE("a scene file above the size limit is refused before it is read") {
  TempDir dir;
  const std::string big = dir / "big.toml";
  { std::ofstream(big) << kHead; }
  fs::resize_file(big, kMaxSceneFileBytes + 1);  // sparse: nothing to read, only its size
  CHECK_THAT(load_error(big), Catch::Contains("big.toml: the file has 64.0 MiB (67108865 bytes); "
                                              "the limit for a scene file is 64.0 MiB"));
}

TEST_CASE("a directory given as the scene is named as such") {
  TempDir dir;
  CHECK(load_error(dir.path.string()) == dir.path.string() + ": is a directory, not a scene file");
}

TEST_CASE("a stream is read up to the limit, then refused") {
  TempDir dir;
  const std::string fifo = dir / "fifo";
  REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
  // A writer with more than the limit: the reader stops one byte past it (and the writer
  // gets EPIPE instead of the signal that would end the test).
  std::signal(SIGPIPE, SIG_IGN);
  std::thread writer([&] {
    const int fd = ::open(fifo.c_str(), O_WRONLY);
    const std::string block(1 << 20, '#');
    for (size_t sent = 0; sent <= kMaxSceneFileBytes + block.size(); sent += block.size())
      if (::write(fd, block.data(), block.size()) < 0) break;  // EPIPE once the reader left
    ::close(fd);
  });
  const std::string message = load_error(fifo);
  writer.join();
  CHECK_THAT(message, Catch::Contains("the stream gave more than 67108864 bytes"));

  // A stream within the limit loads like a file.
  std::thread small([&] {
    std::ofstream(fifo) << kHead
                        << "[[strut]]\nname = \"a\"\nfrom = [0, 0]\nto = [1, 0]\nE = 1e9\n"
                           "area = 1e-4\nelements = 2\nfixed = [\"from\"]\n";
  });
  CHECK(load_scene_file(fifo).struts.size() == 1);
  small.join();
}

TEST_CASE("a private zero device is read only up to the limit") {
  if (::geteuid() != 0) FETIC_SKIP("mknod needs root");
  TempDir dir;
  const std::string zero = dir / "zero";
  REQUIRE(::mknod(zero.c_str(), S_IFCHR | 0600, makedev(1, 5)) == 0);
  CHECK_THAT(load_error(zero), Catch::Contains("the stream gave more than"));
}
