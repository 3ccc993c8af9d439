// `fetic render` killed in the middle of an iteration movie: whatever the signal, every
// frame_*.png in the output directory is a complete PNG (it ends with the IEND chunk and
// decodes). SIGTERM and SIGINT stop the run cleanly: exit status 130, a message, and no
// temporary files left behind. SIGKILL cannot be caught: its temporary files may remain,
// but they never carry the .png name.

#include <catch2/catch.hpp>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include <stb_image.h>
#include "tests/support/child_process.hpp"
#include "tests/support/skip.hpp"

namespace fs = std::filesystem;
using namespace std::chrono_literals;

namespace {

// Load steps of the chain scene, one frame each: long enough to be killed in the middle.
constexpr int kFrames = 600;

int count_frames(const fs::path& directory) {
  int count = 0;
  std::error_code error;
  for (const auto& entry : fs::directory_iterator(directory, error))
    if (entry.path().extension() == ".png") ++count;
  return count;
}

pid_t start_render(const fs::path& out, const fs::path& log, const std::string& movie = "") {
  std::vector<std::string> args{
      "render",       std::string(FETIC_BUNDLED_SCENES_DIR) + "/chain.toml",
      "--method",     "active-set",
      "--load-steps", "0.01:1:" + std::to_string(kFrames),
      "--max-frames", "100000",
      "--size",       "320x200",
      "--threads",    "2",
      "--out",        out.string()};
  if (!movie.empty()) args.insert(args.end(), {"--movie", movie});
  return fetic::test::start_fetic(args, log);
}

void check_complete_pngs(const fs::path& directory) {
  static const std::string iend("\0\0\0\0IEND\xae\x42\x60\x82", 12);
  for (const auto& entry : fs::directory_iterator(directory)) {
    if (entry.path().extension() != ".png") continue;
    INFO(entry.path().string());
    const std::string png = fetic::test::read_bytes(entry.path());
    REQUIRE(png.size() > iend.size());
    CHECK(png.compare(png.size() - iend.size(), iend.size(), iend) == 0);
    int width = 0, height = 0, channels = 0;
    stbi_uc* pixels =
        stbi_load_from_memory(reinterpret_cast<const stbi_uc*>(png.data()),
                              static_cast<int>(png.size()), &width, &height, &channels, 4);
    CHECK(pixels != nullptr);
    CHECK(width == 320);
    CHECK(height == 200);
    stbi_image_free(pixels);
  }
}

}  // namespace

TEST_CASE("fetic render killed in the middle of a movie leaves only complete PNG files") {
  for (const int signal : {SIGKILL, SIGTERM, SIGINT}) {
    const std::string name = signal == SIGKILL ? "kill" : signal == SIGTERM ? "term" : "int";
    DYNAMIC_SECTION("signal " << name) {
      const fs::path out =
          fs::temp_directory_path() / ("fetic_render_" + name + "_" + std::to_string(::getpid()));
      const fs::path log = out.string() + ".log";
      fs::remove_all(out);
      const pid_t child = start_render(out, log);
      REQUIRE(child > 0);

      // Wait (bounded) until a few frames exist, then signal in the middle of the movie.
      if (!fetic::test::wait_for(
              child, [&] { return count_frames(out) >= 5; }, 300s, 5ms)) {
        fetic::test::kill_child(child);
        FAIL("fetic render ended or stalled before 5 frames:\n" << fetic::test::read_bytes(log));
      }
      REQUIRE(::kill(child, signal) == 0);
      const auto [result, output] = fetic::test::wait_ending(child, log, 120s);
      INFO(output);
      REQUIRE(result);
      const int status = *result;

      const int frames = count_frames(out);
      CHECK(frames >= 5);
      CHECK(frames < kFrames);  // it really was interrupted in the middle
      check_complete_pngs(out);

      if (signal == SIGKILL) {
        CHECK(WIFSIGNALED(status));
      } else {
        REQUIRE(WIFEXITED(status));
        CHECK(WEXITSTATUS(status) == 130);
        CHECK_THAT(output, Catch::Contains(std::string("interrupted by ") +
                                           (signal == SIGTERM ? "SIGTERM" : "SIGINT")));
        CHECK_THAT(output, Catch::Contains("complete frames"));
        // Nothing but complete frames: no temporary files remain.
        for (const auto& entry : fs::directory_iterator(out)) {
          INFO(entry.path().string());
          CHECK(entry.path().extension() == ".png");
        }
      }
      fs::remove_all(out);
      fs::remove(log);
    }
  }
}

TEST_CASE("fetic render: SIGTERM while frames stream into ffmpeg stops it, leaves no movie") {
  if (std::system("command -v ffmpeg > /dev/null 2>&1") != 0)
    FETIC_SKIP("ffmpeg is not installed here: not checked");
  const fs::path out =
      fs::temp_directory_path() / ("fetic_render_movie_term_" + std::to_string(::getpid()));
  const fs::path log = out.string() + ".log";
  fs::remove_all(out);
  const std::string movie = (out / "movie.mp4").string();
  const pid_t child = start_render(out, log, movie);
  REQUIRE(child > 0);
  // ffmpeg writes movie.mp4.tmpPID while the frames stream in: signal then.
  const auto has_temporary_movie = [&] {
    std::error_code error;
    for (const auto& entry : fs::directory_iterator(out, error))
      if (entry.path().filename().string().rfind("movie.mp4.tmp", 0) == 0) return true;
    return false;
  };
  if (!fetic::test::wait_for(child, has_temporary_movie, 300s, 2ms)) {
    fetic::test::kill_child(child);
    FAIL("ffmpeg was not seen at work:\n" << fetic::test::read_bytes(log));
  }
  REQUIRE(::kill(child, SIGTERM) == 0);
  const auto [result, output] = fetic::test::wait_ending(child, log, 120s);
  INFO(output);
  REQUIRE(result);
  REQUIRE(WIFEXITED(*result));
  CHECK(WEXITSTATUS(*result) == 130);
  CHECK_THAT(output, Catch::Contains("interrupted by SIGTERM while streaming frames to ffmpeg"));
  CHECK_THAT(output, Catch::Contains("complete frames"));
  CHECK_FALSE(fs::exists(movie));
  CHECK_FALSE(has_temporary_movie());
  CHECK(count_frames(out) < kFrames);  // the frames stream while they render
  check_complete_pngs(out);
  fs::remove_all(out);
  fs::remove(log);
}
