// Output targets (app/output_file.hpp), end to end through the commands: a device node,
// a FIFO or stdout is written directly and keeps being what it is; a symbolic link is
// followed; a lost byte is status 5, never 0; a file of many buffers arrives whole. Device nodes
// are private ones made with mknod in a temporary folder (root only; skipped otherwise): never the
// real /dev.

#include <catch2/catch.hpp>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>

#include <nlohmann/json.hpp>

#include "app/output_file.hpp"
#include "tests/support/process.hpp"
#include "tests/support/skip.hpp"

using namespace fetic::test;
namespace fs = std::filesystem;

namespace {

const std::string kScene = bundled_scene("two_bars.toml");

// Reads a FIFO to its end on a thread (the writer blocks until a reader opens it).
class FifoReader {
 public:
  explicit FifoReader(const std::string& path)
      : thread_([this, path] {
          const int fd = ::open(path.c_str(), O_RDONLY);
          if (fd < 0) return;
          char buffer[4096];
          for (ssize_t n; (n = ::read(fd, buffer, sizeof buffer)) > 0;)
            text_.append(buffer, static_cast<size_t>(n));
          ::close(fd);
        }) {}
  std::string text() {
    thread_.join();
    return text_;
  }

 private:
  std::string text_;
  std::thread thread_;
};

void make_fifo(const std::string& path) {
  REQUIRE(::mkfifo(path.c_str(), 0600) == 0);
}

}  // namespace

TEST_CASE("outputs onto a private null device are written to it and leave it a device",
          "[output]") {
  if (!can_make_devices()) FETIC_SKIP("mknod needs root");
  TempDir dir;
  const std::string null = make_char_device(dir, "null", 1, 3);
  for (const std::vector<std::string>& command :
       {std::vector<std::string>{"solve", kScene, "--json", null},
        {"generate", "--pairs", "2", "-o", null},
        {"bench", kScene, "--repeat", "1", "--csv", null}}) {
    INFO(command[0]);
    const Result r = run_fetic(command);
    INFO(r.err);
    CHECK(r.status == 0);
    CHECK(is_char_device(null));
  }
  CHECK(fs::directory_iterator(dir.path())->path().filename() == "null");  // no temporary left
}

TEST_CASE("a full device (ENOSPC) as output, file or stdout, gives status 5 naming it",
          "[output]") {
  if (!can_make_devices()) FETIC_SKIP("mknod needs root");
  TempDir dir;
  const std::string full = make_char_device(dir, "full", 1, 7);
  for (const std::vector<std::string>& command :
       {std::vector<std::string>{"solve", kScene, "--json", full},
        {"generate", "--pairs", "2", "-o", full},
        {"bench", kScene, "--repeat", "1", "--csv", full}}) {
    INFO(command[0]);
    const Result r = run_fetic(command);
    CHECK(r.status == 5);
    CHECK_THAT(r.err, Catch::Contains(full) && Catch::Contains("No space left on device"));
    CHECK(is_char_device(full));
  }
  // stdout onto the full device: the scene of `generate`, the report of `solve`.
  Streams onto_full;
  onto_full.stdout_path = full;
  const Result generated = run_fetic({"generate", "--pairs", "2"}, onto_full);
  CHECK(generated.status == 5);
  CHECK_THAT(generated.err,
             Catch::Contains("standard output") && Catch::Contains("No space left on device"));
  const Result solved = run_fetic({"solve", kScene}, onto_full);
  CHECK(solved.status == 5);
  CHECK_THAT(solved.err, Catch::Contains("standard output"));
}

TEST_CASE("a closed stdout loses the output: status 5, and no file takes its place", "[output]") {
  TempDir dir;
  Streams closed;
  closed.close_stdout = true;
  const Result generated = run_fetic({"generate", "--pairs", "2"}, closed);
  CHECK(generated.status == 5);
  CHECK_THAT(generated.err, Catch::Contains("standard output"));
  // The result file opened while descriptor 1 is closed must not become stdout.
  const std::string json = dir / "r.json";
  const Result solved = run_fetic({"solve", kScene, "--json", json}, closed);
  CHECK(solved.status == 5);  // the summary was lost
  CHECK(nlohmann::json::parse(read_text(json))["converged"] == true);
}

TEST_CASE("'-' is stdout for every output option, the report then goes to stderr", "[output]") {
  const Result solved = run_fetic({"solve", kScene, "--json", "-"});
  INFO(solved.err);
  REQUIRE(solved.status == 0);
  CHECK(nlohmann::json::parse(solved.out)["converged"] == true);  // nothing else on stdout
  CHECK_THAT(solved.err, Catch::Contains("converged    yes"));
  CHECK_FALSE(fs::exists("-"));

  const Result generated = run_fetic({"generate", "--pairs", "2", "-o", "-"});
  REQUIRE(generated.status == 0);
  CHECK_THAT(generated.out, Catch::StartsWith("# ") && Catch::Contains("[[strut]]"));

  const Result bench = run_fetic({"bench", kScene, "--repeat", "1", "--csv", "-"});
  REQUIRE(bench.status == 0);
  CHECK_THAT(bench.out, Catch::StartsWith("scene,method,unknowns"));
  CHECK_THAT(bench.err, Catch::Contains("solve/AS"));
}

TEST_CASE("a FIFO as output is written directly and stays a FIFO", "[output]") {
  TempDir dir;
  const std::string fifo = dir / "fifo";
  make_fifo(fifo);
  FifoReader reader(fifo);
  const Result r = run_fetic({"solve", kScene, "--json", fifo});
  INFO(r.err);
  CHECK(r.status == 0);
  CHECK(nlohmann::json::parse(reader.text())["converged"] == true);
  CHECK(is_fifo(fifo));

  const std::string fifo2 = dir / "fifo2";
  make_fifo(fifo2);
  FifoReader scene_reader(fifo2);
  CHECK(run_fetic({"generate", "--pairs", "3", "-o", fifo2}).status == 0);
  CHECK_THAT(scene_reader.text(), Catch::Contains("name = \"R3\""));
}

TEST_CASE("SIGTERM while waiting for a FIFO's reader: status 130, the FIFO stays", "[output]") {
  TempDir dir;
  const std::string fifo = dir / "fifo";
  make_fifo(fifo);
  Process process({"solve", kScene, "--json", fifo});
  REQUIRE(process.wait_for_fifo_open());  // solved, blocked opening the FIFO
  process.signal(SIGTERM);
  const Result r = process.wait(std::chrono::seconds(20));
  CHECK(r.status == 130);
  CHECK_THAT(r.err, Catch::Contains(fifo) && Catch::Contains("interrupted by SIGTERM"));
  CHECK(is_fifo(fifo));
}

TEST_CASE("a symbolic link is followed: the target is replaced, the link stays", "[output]") {
  TempDir dir;
  const std::string target = dir / "target.json", link = dir / "link.json";
  { std::ofstream(target) << "old"; }
  ::chmod(target.c_str(), 0640);
  fs::create_symlink("target.json", link);  // relative to the link's folder
  const Result r = run_fetic({"solve", kScene, "--json", link});
  INFO(r.err);
  CHECK(r.status == 0);
  CHECK(is_symlink(link));
  CHECK(nlohmann::json::parse(read_text(target))["converged"] == true);
  CHECK((fs::status(target).permissions() & fs::perms::all) ==
        (fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read));

  // A dangling link: its target is created.
  const std::string dangling = dir / "dangling", created = dir / "created.toml";
  fs::create_symlink(created, dangling);
  CHECK(run_fetic({"generate", "--pairs", "1", "-o", dangling}).status == 0);
  CHECK(is_symlink(dangling));
  CHECK_THAT(read_text(created), Catch::Contains("[[strut]]"));

  // A loop of links is refused.
  fs::create_symlink(dir / "loop_b", dir / "loop_a");
  fs::create_symlink(dir / "loop_a", dir / "loop_b");
  const Result loop = run_fetic({"solve", kScene, "--json", dir / "loop_a"});
  CHECK(loop.status == 5);
  CHECK_THAT(loop.err, Catch::Contains("symbolic links"));
}

TEST_CASE("a link to a private device is followed to the device", "[output]") {
  if (!can_make_devices()) FETIC_SKIP("mknod needs root");
  TempDir dir;
  const std::string full = make_char_device(dir, "full", 1, 7);
  fs::create_symlink(full, dir / "link");
  const Result r = run_fetic({"generate", "--pairs", "1", "-o", dir / "link"});
  CHECK(r.status == 5);
  CHECK(is_symlink(dir / "link"));
  CHECK(is_char_device(full));
}

TEST_CASE("outputs that cannot be written are refused with status 5 and the reason", "[output]") {
  TempDir dir;
  const Result directory = run_fetic({"solve", kScene, "--json", dir.path().string()});
  CHECK(directory.status == 5);
  CHECK_THAT(directory.err, Catch::Contains("is a directory"));

  const Result missing = run_fetic({"generate", "-o", dir / "no/such/folder/s.toml"});
  CHECK(missing.status == 5);
  CHECK_THAT(missing.err, Catch::Contains("No such file or directory"));

  if (can_make_devices()) {
    const std::string block = dir / "block";
    REQUIRE(::mknod(block.c_str(), S_IFBLK | 0600, makedev(7, 200)) == 0);
    const Result disk = run_fetic({"solve", kScene, "--json", block});
    CHECK(disk.status == 5);
    CHECK_THAT(disk.err, Catch::Contains("block device"));
    struct stat info {};
    CHECK((::lstat(block.c_str(), &info) == 0 && S_ISBLK(info.st_mode)));
  }
}

TEST_CASE("a regular file is replaced whole, no temporary file remains", "[output]") {
  TempDir dir;
  const std::string csv = dir / "bench.csv";
  { std::ofstream(csv) << "old contents that are longer than nothing\n"; }
  const Result r = run_fetic({"bench", kScene, "--repeat", "1", "--csv", csv});
  REQUIRE(r.status == 0);
  CHECK_THAT(read_text(csv), Catch::StartsWith("scene,method"));
  int files = 0;
  for ([[maybe_unused]] const auto& entry : fs::directory_iterator(dir.path()))
    ++files;
  CHECK(files == 1);
}

// Whole 1 MiB buffers of a large regular file go past the page cache (O_DIRECT) from the
// ninth on, the partial last one - or any written after a flush left the file at an
// unaligned offset - the ordinary way (app/output_file.cpp, DirectWrites): every byte
// must arrive, in order.
TEST_CASE("a file of many buffers, flushed mid-buffer or not, has every byte in order",
          "[output]") {
  TempDir dir;
  const std::string path = dir / "big.txt";
  constexpr int kLines = 1200000;  // 15 MB, lines of unequal lengths
  const auto line_text = [](int line) {
    return std::to_string(line * 7919LL) + (line % 3 ? " a" : " bcd");
  };
  for (const bool flush_between : {false, true}) {
    INFO("flushed mid-buffer: " << flush_between);
    fetic::app::write_output(path, [&](std::ostream& out) {
      for (int line = 0; line < kLines; ++line) {
        out << line_text(line) << '\n';
        if (flush_between && line == 900000) out.flush();  // after direct writes began
      }
    });
    // Read back line by line (whole copies of 15 MB cost more than the writing here).
    std::ifstream in(path, std::ios::binary);
    int lines = 0;
    bool same = true;
    for (std::string text; same && std::getline(in, text); ++lines)
      same = text == line_text(lines);
    CHECK(same);
    CHECK(lines == kLines);
  }
}
