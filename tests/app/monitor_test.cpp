// `fetic solve --monitor`: one JSON line per iteration, equal to the result file's
// history entry for entry; the working-set changes replay to the final working set; the
// stream can be followed while the solve still runs (a FIFO in a temporary folder).

#include <catch2/catch.hpp>

#include <fcntl.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "tests/support/shell_run.hpp"

extern char** environ;

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

struct Folder {
  fs::path path;
  Folder() {
    path = fs::temp_directory_path() /
           ("fetic_monitor_" + std::to_string(::getpid()) + "_" + std::to_string(std::rand()));
    fs::create_directories(path);
  }
  ~Folder() { fs::remove_all(path); }
  std::string operator/(const std::string& name) const { return (path / name).string(); }
};

using fetic::test::scene;

int run(const std::string& arguments, const std::string& log) {
  const int raw = std::system(
      (std::string(FETIC_EXECUTABLE) + " " + arguments + " > " + log + " 2> " + log + ".err")
          .c_str());
  return WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
}

std::string read_text(const std::string& path) {
  std::ifstream in(path);
  return {std::istreambuf_iterator<char>(in), {}};
}

// The iteration lines, after checking the first line: the version and units header.
std::vector<json> lines_of(const std::string& text) {
  std::vector<json> lines;
  std::istringstream in(text);
  std::string first;
  REQUIRE(std::getline(in, first));
  const json header = json::parse(first);
  CHECK(header["fetic_version"].get<std::string>() == FETIC_VERSION);
  CHECK(header["units"]["length"].is_string());
  CHECK_FALSE(header.contains("iteration"));
  for (std::string line; std::getline(in, line);)
    lines.push_back(json::parse(line));
  return lines;
}

// The lines equal the history entry for entry, and the pairs entered and left replay to
// the final working set of the result file.
void check_against_result(const std::vector<json>& lines, const json& result) {
  const json& history = result["history"];
  REQUIRE(lines.size() == history.size());
  std::vector<bool> active;
  for (const json& contact : result["contacts"])
    for (const json& pair : contact["pairs"])
      active.push_back(pair["active"].get<bool>());
  std::vector<bool> replayed(active.size(), false);
  double previous_time = 0.0;
  for (size_t i = 0; i < lines.size(); ++i) {
    INFO("line " << i << ": " << lines[i].dump());
    CHECK(lines[i]["iteration"] == history[i]["iteration"]);
    CHECK(lines[i]["residual"] == history[i]["residual"]);
    CHECK(lines[i]["active_set"] == history[i]["active_set"]);
    CHECK(lines[i]["load_factor"] == result["load_factor"]);
    CHECK(lines[i]["time"].get<double>() >= previous_time);
    previous_time = lines[i]["time"].get<double>();
    for (const json& k : lines[i]["entered"]) {
      CHECK_FALSE(replayed.at(k.get<size_t>()));
      replayed[k.get<size_t>()] = true;
    }
    for (const json& k : lines[i]["left"]) {
      CHECK(replayed.at(k.get<size_t>()));
      replayed[k.get<size_t>()] = false;
    }
    int size = 0;
    for (bool in : replayed)
      size += in ? 1 : 0;
    CHECK(size == lines[i]["active_set"].get<int>());
  }
  CHECK(replayed == active);
}

}  // namespace

TEST_CASE("solve --monitor lines equal the history of a bar scene") {
  Folder folder;
  const std::string monitor = folder / "monitor.jsonl", result = folder / "result.json";
  for (const char* method : {"active-set", "feti-c"}) {
    INFO(method);
    REQUIRE(run("solve " + scene("thesis.toml") + " --method " + method + " --monitor " + monitor +
                    " --json " + result,
                folder / "log") == 0);
    const json expected = json::parse(read_text(result));
    const auto lines = lines_of(read_text(monitor));
    check_against_result(lines, expected);
  }
}

TEST_CASE("solve --monitor lines equal the history of a plane scene") {
  Folder folder;
  const std::string monitor = folder / "monitor.jsonl", result = folder / "result.json";
  REQUIRE(run("solve " + scene("plane_pair.toml") + " --method feti-c --monitor " + monitor +
                  " --json " + result,
              folder / "log") == 0);
  check_against_result(lines_of(read_text(monitor)), json::parse(read_text(result)));
}

TEST_CASE("solve --monitor-full adds the state, the last one equals the result") {
  Folder folder;
  const std::string result = folder / "result.json";
  // --monitor - : the lines on stdout, the summary on stderr.
  REQUIRE(run("solve " + scene("plane_pair.toml") +
                  " --method feti-c --monitor - --monitor-full 1 --json " + result,
              folder / "out") == 0);
  CHECK_THAT(read_text(folder / "out.err"), Catch::Contains("converged    yes"));
  const auto lines = lines_of(read_text(folder / "out"));
  const json expected = json::parse(read_text(result));
  check_against_result(lines, expected);
  for (const json& line : lines)
    CHECK(line.contains("displacements"));
  const json& last = lines.back();
  REQUIRE(last["displacements"].size() == expected["struts"].size());
  for (size_t s = 0; s < expected["struts"].size(); ++s)
    CHECK(last["displacements"][s] == expected["struts"][s]["displacements"]);
  std::vector<double> forces;
  for (const json& contact : expected["contacts"])
    for (const json& pair : contact["pairs"])
      forces.push_back(pair["force"].get<double>());
  CHECK(last["multipliers"].get<std::vector<double>>() == forces);

  // Every third iteration only.
  REQUIRE(run("solve " + scene("plane_pair.toml") + " --method feti-c --monitor-full 3 --monitor " +
                  (folder / "m3"),
              folder / "out") == 0);
  for (const json& line : lines_of(read_text(folder / "m3")))
    CHECK(line.contains("displacements") == (line["iteration"].get<int>() % 3 == 0));
}

TEST_CASE("solve --monitor is refused without a target or twice on stdout") {
  Folder folder;
  CHECK(run("solve " + scene("thesis.toml") + " --monitor-full 2", folder / "out") == 1);
  CHECK_THAT(read_text(folder / "out.err"), Catch::Contains("--monitor-full needs --monitor"));
  CHECK(run("solve " + scene("thesis.toml") + " --monitor - --json -", folder / "out") == 1);
  CHECK(run("solve " + scene("thesis.toml") + " --monitor " + folder.path.string(),
            folder / "out") == 5);
}

TEST_CASE("solve --monitor can be followed through a FIFO while the solve runs") {
  Folder folder;
  const std::string fifo = folder / "stream", result = folder / "result.json";
  REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
  // The full state every iteration makes the stream far larger than the pipe: the solve
  // cannot end before its reader has drained it, so it must still run after line one.
  const std::string command = std::string("exec ") + FETIC_EXECUTABLE + " solve " +
                              scene("thesis.toml") +
                              " --method active-set --monitor-full 1 --monitor " + fifo +
                              " --json " + result + " > " + (folder / "log") + " 2>&1";
  const char* argv[] = {"/bin/sh", "-c", command.c_str(), nullptr};
  pid_t pid = 0;
  REQUIRE(::posix_spawn(&pid, "/bin/sh", nullptr, nullptr, const_cast<char**>(argv), environ) == 0);
  const int fd = ::open(fifo.c_str(), O_RDONLY);
  REQUIRE(fd >= 0);
  const long capacity = ::fcntl(fd, F_GETPIPE_SZ);
  std::string text;
  char buffer[4096];
  bool running_after_first_line = false;
  size_t after_first_line = 0;
  for (;;) {
    const ssize_t n = ::read(fd, buffer, sizeof buffer);
    if (n <= 0) break;
    text.append(buffer, static_cast<size_t>(n));
    if (after_first_line == 0 && text.find('\n') != std::string::npos) {
      after_first_line = text.size();
      int raw = 0;
      running_after_first_line = ::waitpid(pid, &raw, WNOHANG) == 0;
    }
  }
  ::close(fd);
  int raw = 0;
  REQUIRE(::waitpid(pid, &raw, 0) == pid);
  INFO(read_text(folder / "log"));
  REQUIRE(WIFEXITED(raw));
  REQUIRE(WEXITSTATUS(raw) == 0);
  // What followed the first line did not fit in the pipe: the solve was still running.
  CHECK(text.size() - after_first_line > static_cast<size_t>(capacity));
  CHECK(running_after_first_line);
  check_against_result(lines_of(text), json::parse(read_text(result)));
}
