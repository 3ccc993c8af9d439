// End to end: `fetic render` writes one complete PNG per iteration from the initial state,
// identical run to run; `fetic figures` writes the figures; errors name the file and use
// the documented exit statuses (including no EGL display and no ffmpeg).

#include <catch2/catch.hpp>

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include "tests/support/skip.hpp"

#include "tests/support/shell_run.hpp"

namespace fs = std::filesystem;

namespace {

struct Run {
  int status = -1;
  std::string output;
};

// Runs a shell command line, returns its status and output.
Run run_program(const std::string& command_line) {
  // One log per process: the test cases run in parallel.
  const std::string log =
      (fs::temp_directory_path() / ("fetic_render_test_" + std::to_string(::getpid()) + ".txt"))
          .string();
  const std::string command = command_line + " > " + log + " 2>&1";
  const int raw = std::system(command.c_str());
  Run result;
  result.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  std::ifstream in(log);
  result.output.assign(std::istreambuf_iterator<char>(in), {});
  return result;
}

Run run(const std::string& arguments, const std::string& environment = "") {
  return run_program(environment + " " + std::string(FETIC_EXECUTABLE) + " " + arguments);
}

using fetic::test::scene;

fs::path fresh_directory(const std::string& name) {
  const fs::path directory = fs::temp_directory_path() / (name + "_" + std::to_string(::getpid()));
  fs::remove_all(directory);
  return directory;
}

std::string bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

std::vector<std::string> files(const fs::path& directory) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(directory))
    names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

}  // namespace

TEST_CASE("fetic render: the initial state and one frame per iteration, identical run to run") {
  const fs::path first = fresh_directory("fetic_render_frames_1");
  const fs::path second = fresh_directory("fetic_render_frames_2");
  const std::string common = scene("thesis.toml") + " --method active-set --size 320x200 --out ";
  const Run a = run("render " + common + first.string());
  INFO(a.output);
  REQUIRE(a.status == 0);
  REQUIRE(run("render " + common + second.string()).status == 0);
  const auto names = files(first);
  // The active-set method takes 14 iterations on the thesis scene: 15 frames.
  REQUIRE(names.size() == 15);
  CHECK(names.front() == "frame_0000.png");
  CHECK(names.back() == "frame_0014.png");
  for (const std::string& name : names) {
    const std::string png = bytes(first / name);
    CHECK(png.substr(1, 3) == "PNG");  // complete files only: no temporaries left
    CHECK(png == bytes(second / name));
  }
}

TEST_CASE("fetic render --method feti-c: one frame per FETI-C iteration, identical run to run") {
  // The iteration count comes from `fetic solve`: the renderer drives the same stepper.
  const fs::path json =
      fs::temp_directory_path() / ("fetic_render_feti_c_" + std::to_string(::getpid()) + ".json");
  REQUIRE(run("solve " + scene("thesis.toml") + " --method feti-c --quiet --json " + json.string())
              .status == 0);
  const std::string result = bytes(json);
  const auto at = result.find("\"iterations\":");
  REQUIRE(at != std::string::npos);
  const int iterations = std::stoi(result.substr(at + 13));
  fs::remove(json);

  const fs::path first = fresh_directory("fetic_render_feti_c_1");
  const fs::path second = fresh_directory("fetic_render_feti_c_2");
  const std::string common = scene("thesis.toml") + " --method feti-c --size 256x160 --out ";
  const Run a = run("render " + common + first.string());
  INFO(a.output);
  REQUIRE(a.status == 0);
  REQUIRE(run("render " + common + second.string()).status == 0);
  const auto names = files(first);
  CHECK(names.size() == static_cast<std::size_t>(iterations + 1));
  for (const std::string& name : names)
    CHECK(bytes(first / name) == bytes(second / name));
}

TEST_CASE("fetic render: final state, load steps, stress colours") {
  const fs::path final_only = fresh_directory("fetic_render_final");
  CHECK(run("render " + scene("chain.toml") + " --method active-set --final --size 200x120 --out " +
            final_only.string())
            .status == 0);
  CHECK(files(final_only) == std::vector<std::string>{"frame_0000.png"});

  const fs::path steps = fresh_directory("fetic_render_steps");
  const Run r =
      run("render " + scene("chain.toml") +
          " --method active-set --load-steps 0.25:1:4 --color stress --size 200x120 --out " +
          steps.string());
  INFO(r.output);
  CHECK(r.status == 0);
  CHECK(files(steps).size() == 4);
}

TEST_CASE("fetic render --color moment: frame scenes coloured by bending moment") {
  const fs::path moment = fresh_directory("fetic_render_moment");
  const fs::path plain = fresh_directory("fetic_render_moment_plain");
  const std::string common =
      scene("frame_portal_sway.toml") + " --method active-set --final --size 320x200 --out ";
  const Run r = run("render " + common + moment.string() + " --color moment");
  INFO(r.output);
  REQUIRE(r.status == 0);
  REQUIRE(files(moment) == std::vector<std::string>{"frame_0000.png"});
  REQUIRE(run("render " + common + plain.string() + " --color subdomain").status == 0);
  CHECK(bytes(moment / "frame_0000.png") != bytes(plain / "frame_0000.png"));

  // A saved view's "color": "moment" draws the same picture.
  const fs::path viewed = fresh_directory("fetic_render_moment_view");
  const fs::path view =
      fs::temp_directory_path() / ("fetic_render_moment_" + std::to_string(::getpid()) + ".json");
  std::ofstream(view) << R"({"fetic_view": 1, "color": "moment"})";
  REQUIRE(run("render " + common + viewed.string() + " --view " + view.string()).status == 0);
  CHECK(bytes(viewed / "frame_0000.png") == bytes(moment / "frame_0000.png"));

  // Bars carry no bending moment: refused, by option or by view, naming the scene.
  const fs::path bars = fresh_directory("fetic_render_moment_bars");
  const Run refused =
      run("render " + scene("two_bars.toml") + " --color moment --final --out " + bars.string());
  CHECK(refused.status == 1);
  CHECK_THAT(refused.output, Catch::Contains("two_bars.toml: colouring by bending moment needs a "
                                             "frame scene"));
  CHECK(run("render " + scene("two_bars.toml") + " --final --view " + view.string() + " --out " +
            bars.string())
            .status == 1);
  // ... unless the command line asks for another colouring.
  CHECK(run("render " + scene("two_bars.toml") + " --final --view " + view.string() +
            " --color stress --size 200x120 --out " + bars.string())
            .status == 0);
  CHECK(run("render " + common + moment.string() + " --color moments").status == 1);
  fs::remove(view);
}

TEST_CASE("fetic render --color strut: one colour per strut, as in a view file") {
  const fs::path by_strut = fresh_directory("fetic_render_strut");
  const fs::path by_view = fresh_directory("fetic_render_strut_view");
  const fs::path by_subdomain = fresh_directory("fetic_render_strut_subdomain");
  const std::string common =
      scene("thesis.toml") + " --method active-set --final --size 320x200 --out ";
  REQUIRE(run("render " + common + by_strut.string() + " --color strut").status == 0);
  REQUIRE(run("render " + common + by_subdomain.string() + " --color subdomain").status == 0);
  const fs::path view =
      fs::temp_directory_path() / ("fetic_render_strut_" + std::to_string(::getpid()) + ".json");
  std::ofstream(view) << R"({"fetic_view": 1, "color": "strut"})";
  REQUIRE(run("render " + common + by_view.string() + " --view " + view.string()).status == 0);
  CHECK(bytes(by_strut / "frame_0000.png") == bytes(by_view / "frame_0000.png"));
  // The thesis' struts have two subdomains each: coloured per strut, the picture differs.
  CHECK(bytes(by_strut / "frame_0000.png") != bytes(by_subdomain / "frame_0000.png"));
  fs::remove(view);
}

TEST_CASE("fetic render: errors name the file and use the documented statuses") {
  const fs::path out = fresh_directory("fetic_render_errors");
  const Run refused = run("render " + scene("thesis.toml") + " --method cg --out " + out.string());
  CHECK(refused.status == 3);
  CHECK_THAT(refused.output, Catch::Contains("thesis.toml: conjugate gradients"));

  const Run missing = run("render no_such_scene.toml --out " + out.string());
  CHECK(missing.status == 2);
  CHECK_THAT(missing.output, Catch::Contains("no_such_scene.toml"));

  CHECK(run("render " + scene("thesis.toml") + " --size 10x10 --out " + out.string()).status == 1);
  CHECK(run("render " + scene("thesis.toml") + " --load-steps 1:2 --out " + out.string()).status ==
        1);
  CHECK(run("render " + scene("thesis.toml") + " --final --every-iteration --out " + out.string())
            .status == 1);

  const Run too_many = run("render " + scene("thesis.toml") +
                           " --method active-set --max-frames 3 --out " + out.string());
  CHECK(too_many.status == 1);
  CHECK_THAT(too_many.output, Catch::Contains("--max-frames 3"));
}

TEST_CASE("fetic render: no EGL display is a clear error with status 6") {
  // GLVND finds no EGL vendor library: as on a machine without Mesa's EGL.
  const fs::path out = fresh_directory("fetic_render_no_display");
  const Run r =
      run("render " + scene("two_bars.toml") + " --method active-set --out " + out.string(),
          "__EGL_VENDOR_LIBRARY_FILENAMES=/nonexistent/vendor.json");
  CHECK(r.status == 6);
  CHECK_THAT(r.output, Catch::Contains(out.string() + ": cannot render: no EGL display"));
}

TEST_CASE("fetic render --movie: an mp4 with ffmpeg, a clear message without it") {
  const fs::path out = fresh_directory("fetic_render_movie");
  const std::string movie = (out / "movie.mp4").string();
  const std::string arguments = "render " + scene("two_bars.toml") +
                                " --method active-set --size 96x64 --out " + out.string() +
                                " --movie " + movie;
  const Run without = run(arguments, "PATH=/nonexistent");
  CHECK(without.status == 5);
  CHECK_THAT(without.output, Catch::Contains(movie + ": ffmpeg is not installed"));
  CHECK_FALSE(fs::exists(movie));

  if (std::system("command -v ffmpeg > /dev/null 2>&1") != 0)
    FETIC_SKIP("ffmpeg is not installed here: the movie itself is not checked");
  const Run with = run(arguments);
  INFO(with.output);
  CHECK(with.status == 0);
  REQUIRE(fs::exists(movie));
  CHECK(fs::file_size(movie) > 1000);

  // --movie alone: the frames stream into ffmpeg, no PNG is written; ffprobe counts the
  // movie's frames (one per iteration, as many as the PNG run wrote) and its size.
  const fs::path alone = fresh_directory("fetic_render_movie_alone");
  fs::create_directories(alone);
  const std::string streamed = (alone / "streamed.mp4").string();
  const Run only = run("render " + scene("two_bars.toml") +
                       " --method active-set --size 96x64 --samples 1 --movie " + streamed);
  INFO(only.output);
  CHECK(only.status == 0);
  REQUIRE(fs::exists(streamed));
  CHECK(files(alone) == std::vector<std::string>{"streamed.mp4"});
  const Run probe = run_program(
      "ffprobe -v error -count_frames -select_streams v:0 -show_entries "
      "stream=nb_read_frames,width,height -of csv=p=0 " +
      streamed);
  INFO(probe.output);
  CHECK(probe.status == 0);
  const auto pngs = files(out);
  const std::size_t png_frames =
      std::count_if(pngs.begin(), pngs.end(),
                    [](const std::string& name) { return name.rfind("frame_", 0) == 0; });
  CHECK(probe.output == "96,64," + std::to_string(png_frames) + "\n");

  // Neither --out nor --movie: nothing to write is a usage error.
  CHECK(run("render " + scene("two_bars.toml")).status == 1);
}

TEST_CASE("fetic figures: figures by id, and the thesis scene named when it is missing") {
  const fs::path out = fresh_directory("fetic_figures");
  const Run r = run("figures --size 400x300 --figure 2.1 --figure 3.2 --out " + out.string());
  INFO(r.output);
  CHECK(r.status == 0);
  CHECK(files(out) ==
        std::vector<std::string>{"fig2_1_quadratic_forms.png", "fig3_2_steepest_descent.png"});

  const Run missing =
      run("figures --size 400x300 --figure 9.3 --scene no_thesis.toml --out " + out.string());
  CHECK(missing.status == 2);
  CHECK_THAT(missing.output, Catch::Contains("no_thesis.toml"));
}
