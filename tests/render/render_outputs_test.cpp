// `fetic render --movie` onto the targets of app/output_file.hpp: a private full device
// (status 5, the node stays), a FIFO (a fragmented mp4 arrives through it), a symbolic
// link (followed) and stdout ("-", the report on stderr); SIGTERM while ffmpeg waits for
// the FIFO's reader.

#include <catch2/catch.hpp>

#include <sys/stat.h>

#include <cerrno>
#include <csignal>

#include <cstdlib>
#include <fstream>
#include <string>
#include <thread>

#include "tests/support/process.hpp"
#include "tests/support/skip.hpp"

using namespace fetic::test;
namespace fs = std::filesystem;

namespace {

const std::vector<std::string> kRender = {
    "render", bundled_scene("two_bars.toml"), "--final", "--size", "64x48", "--movie"};

std::vector<std::string> render_to(const std::string& movie) {
  std::vector<std::string> command = kRender;
  command.push_back(movie);
  return command;
}

bool has_ffmpeg() {
  return std::system("command -v ffmpeg > /dev/null 2>&1") == 0;
}

// An mp4 starts with its ftyp box: 4 bytes of size, then "ftyp".
bool looks_like_mp4(const std::string& bytes) {
  return bytes.size() > 1000 && bytes.compare(4, 4, "ftyp") == 0;
}

}  // namespace

TEST_CASE("render --movie onto a FIFO, a link and stdout", "[output]") {
  if (!has_ffmpeg()) FETIC_SKIP("ffmpeg is not installed");
  TempDir dir;
  const std::string fifo = dir / "movie.fifo";
  REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
  std::string received;
  std::thread reader([&] { received = read_text(fifo); });
  const Result streamed = run_fetic(render_to(fifo));
  reader.join();
  INFO(streamed.err);
  CHECK(streamed.status == 0);
  CHECK(looks_like_mp4(received));
  CHECK(is_fifo(fifo));

  const std::string target = dir / "movie.mp4";
  fs::create_symlink("movie.mp4", dir / "link.mp4");
  const Result linked = run_fetic(render_to(dir / "link.mp4"));
  CHECK(linked.status == 0);
  CHECK(is_symlink(dir / "link.mp4"));
  CHECK(looks_like_mp4(read_text(target)));

  const Result out = run_fetic(render_to("-"));
  CHECK(out.status == 0);
  CHECK(looks_like_mp4(out.out));
  CHECK_THAT(out.err, Catch::Contains("movie        -"));
}

TEST_CASE("render --movie onto a private full device: status 5, the device stays", "[output]") {
  if (!has_ffmpeg()) FETIC_SKIP("ffmpeg is not installed");
  if (!can_make_devices()) FETIC_SKIP("mknod needs root");
  TempDir dir;
  const std::string full = make_char_device(dir, "full", 1, 7);
  const Result r = run_fetic(render_to(full));
  CHECK(r.status == 5);
  CHECK_THAT(r.err, Catch::Contains(full));
  CHECK(is_char_device(full));
}

TEST_CASE("SIGTERM while ffmpeg waits for the movie FIFO's reader: 130, ffmpeg ended", "[output]") {
  if (!has_ffmpeg()) FETIC_SKIP("ffmpeg is not installed");
  TempDir dir;
  const std::string fifo = dir / "movie.fifo";
  REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
  std::vector<std::string> steps = render_to(fifo);
  steps[2] = "--load-steps";  // several frames: fetic blocks on the full pipe as well
  steps.insert(steps.begin() + 3, "0:1:20");
  for (const auto& command : {render_to(fifo), steps}) {
    Process process(command);
    const pid_t ffmpeg = process.wait_for_child_fifo_open();
    REQUIRE(ffmpeg > 0);
    process.signal(SIGTERM);
    const Result r = process.wait(std::chrono::seconds(30));
    INFO(r.err);
    CHECK(r.status == 130);
    CHECK_THAT(r.err, Catch::Contains(fifo) && Catch::Contains("interrupted by SIGTERM"));
    // ffmpeg only counts a SIGTERM while it blocks in open(); fetic must end it anyway.
    CHECK((::kill(ffmpeg, 0) != 0 && errno == ESRCH));
    CHECK(is_fifo(fifo));
  }
}

TEST_CASE("frames onto a file, a dangling link or an empty name: status 5 naming what is there",
          "[output]") {
  TempDir dir;
  const std::string file = dir / "a_file";
  std::ofstream(file) << "kept\n";
  const Result onto_file = run_fetic(
      {"render", bundled_scene("two_bars.toml"), "--final", "--size", "64x48", "--out", file});
  CHECK(onto_file.status == 5);
  CHECK_THAT(onto_file.err, Catch::Contains(file + ": is not a directory"));
  CHECK(read_text(file) == "kept\n");

  const std::string link = dir / "link";
  fs::create_symlink("missing/frames", link);
  const Result dangling = run_fetic(
      {"render", bundled_scene("two_bars.toml"), "--final", "--size", "64x48", "--out", link});
  CHECK(dangling.status == 5);
  CHECK_THAT(
      dangling.err,
      Catch::Contains(link + ": is a symbolic link to 'missing/frames', which does not exist"));

  const Result empty = run_fetic({"figures", "--figure", "2.1", "--out", ""});
  CHECK(empty.status == 1);
  CHECK_THAT(empty.err, Catch::Contains("--out: an empty name writes nothing"));
}
