// `fetic solve` under mpirun, end to end: the result file is the serial one plus "ranks"
// and "subdomains_per_rank"; rank 0 alone reports; every failure ends every process with
// the documented status and one message; an interrupt stops every process quickly and
// leaves no partial file; commands that do not run distributed are refused. Every run
// has a deadline (`timeout`), so a hang fails the test instead of blocking CI.

#include <catch2/catch.hpp>

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "tests/support/shell_run.hpp"

namespace {

namespace fs = std::filesystem;

using Run = fetic::test::ShellRun;

const std::string kMpirun = std::string(FETIC_MPIEXEC) + " --allow-run-as-root --oversubscribe";

std::string temporary(const std::string& name) {
  return fetic::test::temporary_path("fetic_mpi_" + name);
}

// A hung job fails the test instead of the whole ctest run.
Run run(const std::string& command) {
  return fetic::test::run_shell("timeout 120 " + command);
}

Run run_fetic(const std::string& arguments, int processes = 0) {
  const std::string launcher =
      processes > 0 ? kMpirun + " -np " + std::to_string(processes) + " " : std::string();
  return run(launcher + FETIC_EXECUTABLE + " " + arguments);
}

using fetic::test::scene;

int occurrences(const std::string& text, const std::string& what) {
  int count = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1))
    ++count;
  return count;
}

nlohmann::json read_json(const std::string& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

// Largest difference of the displacements and contact forces of two result files,
// relative to the largest value of each.
void require_same_result(const nlohmann::json& a, const nlohmann::json& b) {
  REQUIRE(a["struts"].size() == b["struts"].size());
  double scale = 0.0, difference = 0.0;
  for (size_t s = 0; s < a["struts"].size(); ++s)
    for (size_t n = 0; n < a["struts"][s]["displacements"].size(); ++n)
      for (int c = 0; c < 2; ++c) {
        const double x = a["struts"][s]["displacements"][n][c];
        const double y = b["struts"][s]["displacements"][n][c];
        scale = std::max(scale, std::abs(x));
        difference = std::max(difference, std::abs(x - y));
      }
  CHECK(difference <= 1e-10 * scale);
  double force_scale = 0.0, force_difference = 0.0;
  for (size_t c = 0; c < a["contacts"].size(); ++c)
    for (size_t p = 0; p < a["contacts"][c]["pairs"].size(); ++p) {
      const auto& x = a["contacts"][c]["pairs"][p];
      const auto& y = b["contacts"][c]["pairs"][p];
      CHECK(x["active"] == y["active"]);
      force_scale = std::max(force_scale, x["force"].get<double>());
      force_difference =
          std::max(force_difference, std::abs(x["force"].get<double>() - y["force"].get<double>()));
    }
  CHECK(force_difference <= 1e-10 * force_scale);
  // Frame scenes: the node rotations and the bending moments too.
  for (const char* field : {"rotations", "bending_moment"}) {
    double field_scale = 0.0, field_difference = 0.0;
    for (size_t s = 0; s < a["struts"].size(); ++s) {
      if (!a["struts"][s].contains(field)) continue;
      REQUIRE(b["struts"][s].contains(field));
      for (size_t n = 0; n < a["struts"][s][field].size(); ++n) {
        const double x = a["struts"][s][field][n], y = b["struts"][s][field][n];
        field_scale = std::max(field_scale, std::abs(x));
        field_difference = std::max(field_difference, std::abs(x - y));
      }
    }
    INFO(field);
    CHECK(field_difference <= 1e-10 * field_scale);
  }
  CHECK(a["iterations"] == b["iterations"]);
  CHECK(a["converged"] == b["converged"]);
}

// A plane scene whose second strut is far too thin for double precision: its subdomain
// stiffness is singular beyond the rigid-body modes. Both struts are clamped, so the
// scene is valid; distributed over two processes the thin strut lands on rank 1.
std::string write_singular_scene() {
  const std::string path = temporary("singular.toml");
  std::ofstream out(path);
  out << "model = \"plane\"\n"
         "[defaults]\nE = 2.1e11\nnu = 0.3\nthickness = 0.01\nelements = 4\nelements_across = 1\n"
         "subdomains = 2\n"
         "[[strut]]\nname = \"sturdy\"\nfrom = [0.0, 0.0]\nto = [1.0, 0.0]\nheight = 0.1\n"
         "fixed = [\"from\"]\n"
         "[[strut]]\nname = \"hair\"\nfrom = [0.0, 1.0]\nto = [1.0, 1.0]\nheight = 1e-12\n"
         "fixed = [\"from\"]\n"
         "[[load]]\nstrut = \"sturdy\"\nat = \"to\"\nforce = [100.0, 0.0]\n";
  return path;
}

}  // namespace

TEST_CASE("mpirun -np 3 fetic solve writes the serial result, with ranks and subdomains per rank") {
  const std::string serial_json = temporary("serial.json"), mpi_json = temporary("mpi.json");
  const Run serial = run_fetic("solve " + scene("thesis.toml") + " --json " + serial_json);
  REQUIRE(serial.status == 0);
  const Run distributed = run_fetic("solve " + scene("thesis.toml") + " --json " + mpi_json, 3);
  INFO(distributed.output);
  REQUIRE(distributed.status == 0);
  CHECK(occurrences(distributed.output, "converged    yes") == 1);  // rank 0 alone reports
  const nlohmann::json a = read_json(serial_json), b = read_json(mpi_json);
  CHECK(a["ranks"] == 1);
  CHECK(b["ranks"] == 3);
  REQUIRE(b["subdomains_per_rank"].size() == 3);
  int subdomains = 0;
  for (int count : b["subdomains_per_rank"]) {
    CHECK(count > 0);
    subdomains += count;
  }
  CHECK(subdomains == 200);  // 100 struts, 2 subdomains each
  require_same_result(a, b);
  fs::remove(serial_json);
  fs::remove(mpi_json);
}

TEST_CASE(
    "mpirun -np 2 fetic solve: plane and frame scenes, a load sweep and MPRGP as in one process") {
  for (const std::string& arguments :
       {scene("plane_pair.toml") + " --preconditioner lumped",
        scene("chain.toml") + " --load-steps 0:2:5",
        scene("thesis.toml") + " --method mprgp --load-steps 0.5:1:3",
        scene("frame_truss_bridge.toml"), scene("frame_scaffold.toml") + " --method mprgp"}) {
    const std::string serial_json = temporary("serial.json"), mpi_json = temporary("mpi.json");
    REQUIRE(run_fetic("solve " + arguments + " --json " + serial_json).status == 0);
    const Run distributed = run_fetic("solve " + arguments + " --json " + mpi_json, 2);
    INFO(arguments << "\n" << distributed.output);
    REQUIRE(distributed.status == 0);
    require_same_result(read_json(serial_json), read_json(mpi_json));
    fs::remove(serial_json);
    fs::remove(mpi_json);
  }
}

TEST_CASE("under mpirun every failure gives one message and the same status on every process") {
  SECTION("an invalid scene: 2") {
    const Run r = run_fetic("solve " + std::string(FETIC_BUNDLED_SCENES_DIR) +
                                "/../tests/scenes/invalid/strut_negative_E.toml",
                            3);
    INFO(r.output);
    CHECK(r.status == 2);
    CHECK(occurrences(r.output, "'E' must be greater than 0") == 1);
  }
  SECTION("a singular subdomain on rank 1: 3") {
    const std::string path = write_singular_scene();
    const Run serial = run_fetic("solve " + path);
    const Run r = run_fetic("solve " + path, 2);
    INFO(serial.output << "\n---\n" << r.output);
    CHECK(serial.status == 3);
    CHECK(r.status == 3);
    CHECK(occurrences(r.output, "strut 'hair': the stiffness") == 1);
    fs::remove(path);
  }
  SECTION("no convergence: 4, and the result file says so") {
    const std::string json = temporary("capped.json");
    const Run r =
        run_fetic("solve " + scene("plane_pair.toml") + " --max-iterations 3 --json " + json, 3);
    INFO(r.output);
    CHECK(r.status == 4);
    CHECK(occurrences(r.output, "did not converge") == 1);
    CHECK(read_json(json)["converged"] == false);
    fs::remove(json);
  }
  SECTION("a method that does not run distributed: 1") {
    const Run r = run_fetic("solve " + scene("thesis.toml") + " --method active-set", 2);
    CHECK(r.status == 1);
    CHECK(occurrences(r.output, "runs in one process") == 1);
    CHECK(occurrences(r.output, "feti, feti-c, mprgp or feti-dp") == 1);
  }
  SECTION("a command that does not run distributed: 1") {
    const Run r = run_fetic("render " + scene("thesis.toml") + " --out " + temporary("frames"), 2);
    CHECK(r.status == 1);
    CHECK(occurrences(r.output, "runs in one process") == 1);
    CHECK_FALSE(fs::exists(temporary("frames")));
  }
}

// A distributed solve started in the background: by default a long load sweep on 3
// processes; else `arguments` (the result file is added) on `processes`.
class LongSolve {
 public:
  explicit LongSolve(const std::string& arguments = scene("chain.toml") +
                                                    " --load-steps 0:1:100000",
                     int processes = 3) {
    const std::string command = kMpirun + " -np " + std::to_string(processes) + " " +
                                FETIC_EXECUTABLE + " solve " + arguments + " --json " + json_;
    child_ = fork();
    if (child_ == 0) {
      const int out = ::open(log_.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      dup2(out, 1);
      dup2(out, 2);
      execl("/bin/sh", "sh", "-c", ("exec " + command).c_str(), static_cast<char*>(nullptr));
      _exit(127);
    }
  }
  ~LongSolve() {
    if (!ended_) {
      ::kill(child_, SIGKILL);
      ::waitpid(child_, &raw_, 0);
    }
    fs::remove(log_);
    fs::remove(json_);
  }

  // Waits until the sweep runs (its first step printed), at most 60 s.
  bool wait_until_running() {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    while (std::chrono::steady_clock::now() < deadline) {
      if (output().find("t = ") != std::string::npos) return ranks().size() == 3;
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    return false;
  }
  // Waits until `count` processes run, then `settle` more seconds (at most 60 s in all).
  bool wait_for_processes(size_t count, double settle) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    while (std::chrono::steady_clock::now() < deadline) {
      if (ranks().size() == count) {
        std::this_thread::sleep_for(std::chrono::duration<double>(settle));
        return ranks().size() == count;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    return false;
  }
  // The fetic processes mpirun started (its children) that still run: a process that
  // has exited stays a zombie until mpirun collects it, which mpirun may do late.
  std::vector<pid_t> ranks() const {
    const std::string list = temporary("ranks.txt");
    std::system(("ps --ppid " + std::to_string(child_) + " -o pid=,stat=,comm= > " + list).c_str());
    std::ifstream in(list);
    std::vector<pid_t> pids;
    pid_t pid;
    std::string state, name;
    while (in >> pid >> state >> name)
      if (name == "fetic" && state.find('Z') == std::string::npos) pids.push_back(pid);
    fs::remove(list);
    return pids;
  }
  // Seconds from now until no fetic process is left, and until mpirun has exited.
  std::pair<double, double> time_to_stop() {
    const auto sent = std::chrono::steady_clock::now();
    double ranks_gone = -1.0;
    while (std::chrono::steady_clock::now() - sent < std::chrono::seconds(20)) {
      const double now =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - sent).count();
      if (ranks_gone < 0 && ranks().empty()) ranks_gone = now;
      if (::waitpid(child_, &raw_, WNOHANG) == child_) {
        ended_ = true;
        return {ranks_gone < 0 ? now : ranks_gone, now};
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    return {ranks_gone, -1.0};
  }
  pid_t mpirun() const { return child_; }
  int status() const { return WIFEXITED(raw_) ? WEXITSTATUS(raw_) : -1; }
  std::string output() const {
    std::ifstream in(log_);
    return std::string(std::istreambuf_iterator<char>(in), {});
  }
  // An interrupted solve writes its result file with the steps done so far (rank 0,
  // whole: renamed into place), never a temporary file left behind.
  bool wrote_interrupted_result() const {
    if (!fs::exists(json_)) return false;
    const nlohmann::json result = read_json(json_);
    const size_t steps = result.at("steps").size();
    return result.at("ranks") == 3 && steps >= 1 && steps < 100000;
  }
  bool left_temporaries() const {
    for (const auto& entry : fs::directory_iterator(fs::temp_directory_path()))
      if (entry.path().filename().string().rfind(fs::path(json_).filename().string() + ".", 0) == 0)
        return true;
    return false;
  }
  bool wrote_result() const { return fs::exists(json_); }

 private:
  std::string json_ = temporary("interrupted.json"), log_ = temporary("interrupt_log.txt");
  pid_t child_ = -1;
  int raw_ = 0;
  bool ended_ = false;
};

TEST_CASE(
    "SIGTERM to one process stops all of them within a second: status 130, the iterate marked "
    "interrupted") {
  // As a batch system's kill of one task: the processes agree between two iterations.
  LongSolve solve;
  REQUIRE(solve.wait_until_running());
  ::kill(solve.ranks()[1], SIGTERM);
  const auto [ranks_gone, mpirun_gone] = solve.time_to_stop();
  const std::string output = solve.output();
  INFO("processes gone after " << ranks_gone << " s, mpirun after " << mpirun_gone << " s\n"
                               << output);
  REQUIRE(mpirun_gone >= 0.0);
  CHECK(ranks_gone < 5.0);  // a hang check, not a speed check: shared machines stall
  CHECK(solve.status() == 130);
  CHECK(occurrences(output, "interrupted by SIGTERM") == 1);
  CHECK(solve.wrote_interrupted_result());
  CHECK_FALSE(solve.left_temporaries());
}

TEST_CASE("SIGTERM and SIGINT to mpirun stop every process, no partial file") {
  // mpirun may end rank 0 while it writes: then no file, else a whole one marked
  // interrupted; never a partial or temporary one.
  // mpirun forwards either as SIGTERM, after its own grace period (Open MPI 4.1:
  // odls_base_sigkill_timeout, 1 s), and then exits with 1 whatever the processes return
  // (they return 130). While it tears the job down it may no longer forward the
  // processes' last output, so rank 0's message is not required here.
  for (int signal : {SIGTERM, SIGINT}) {
    LongSolve solve;
    REQUIRE(solve.wait_until_running());
    ::kill(solve.mpirun(), signal);
    const auto [ranks_gone, mpirun_gone] = solve.time_to_stop();
    const std::string output = solve.output();
    INFO("signal " << signal << ": processes gone after " << ranks_gone << " s, mpirun after "
                   << mpirun_gone << " s\n"
                   << output);
    REQUIRE(mpirun_gone >= 0.0);
    // mpirun's grace period, then fetic's own stop (2.0 s measured, quiet machine): a hang
    // check with room for a busy machine, not a speed check.
    CHECK(ranks_gone < 8.0);
    CHECK(mpirun_gone < 10.0);
    CHECK(solve.status() != 0);
    CHECK(occurrences(output, "interrupted by SIGTERM") <= 1);
    if (solve.wrote_result()) CHECK(solve.wrote_interrupted_result());
    CHECK_FALSE(solve.left_temporaries());
  }
}

namespace {

// The MPI rank of a process mpirun started (Open MPI puts it in the environment).
int rank_of(pid_t pid) {
  std::ifstream in("/proc/" + std::to_string(pid) + "/environ");
  const std::string prefix = "OMPI_COMM_WORLD_RANK=";
  for (std::string entry; std::getline(in, entry, '\0');)
    if (entry.rfind(prefix, 0) == 0) return std::stoi(entry.substr(prefix.size()));
  return -1;
}

}  // namespace

// Rank 0 waits for a reader of its result FIFO (or monitor FIFO) that never comes while
// rank 1 waits for it in the next collective. A signal to either process, or to mpirun,
// must end both: the process that gets it tells the other (a stop notice; the waits poll
// for it), and rank 0 says why it stopped.
TEST_CASE("under mpirun a signal ends a run whose rank 0 waits for a FIFO's reader: 130") {
  const std::string fifo = temporary("reader_never_comes.fifo");
  fs::remove(fifo);
  REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
  struct Case {
    const char* what;
    bool monitor;  // the FIFO is the monitor stream, else the result file
    int target;    // 0, 1: that rank's process; -1: mpirun
    int signal;
  };
  for (const Case& c : {Case{"--json FIFO, SIGTERM to rank 1", false, 1, SIGTERM},
                        Case{"--json FIFO, SIGINT to rank 1", false, 1, SIGINT},
                        Case{"--json FIFO, SIGTERM to rank 0", false, 0, SIGTERM},
                        Case{"--monitor FIFO, SIGTERM to rank 1", true, 1, SIGTERM},
                        Case{"--json FIFO, SIGTERM to mpirun", false, -1, SIGTERM}}) {
    INFO(c.what);
    // The result file (LongSolve's) is a link to the FIFO, made before the run starts.
    if (!c.monitor) fs::create_symlink(fifo, temporary("interrupted.json"));
    LongSolve solve(scene("thesis.toml") + (c.monitor ? " --monitor " + fifo : ""), 2);
    REQUIRE(solve.wait_for_processes(2, 2.0));  // the set-up takes a fraction of this
    pid_t target = solve.mpirun();
    for (pid_t pid : solve.ranks())
      if (rank_of(pid) == c.target) target = pid;
    REQUIRE((c.target < 0 || target != solve.mpirun()));
    ::kill(target, c.signal);
    const auto [ranks_gone, mpirun_gone] = solve.time_to_stop();
    const std::string output = solve.output();
    INFO("processes gone after " << ranks_gone << " s, mpirun after " << mpirun_gone << " s\n"
                                 << output);
    REQUIRE(mpirun_gone >= 0.0);  // without the stop notice: no end at all
    CHECK(ranks_gone < 8.0);      // a hang check, not a speed check
    CHECK(solve.status() != 0);
    if (c.target >= 0) {  // (mpirun may no longer pass the processes' output on)
      CHECK(solve.status() == 130);
      // One message per event: the FIFO's, and - when the signal came before the solve had
      // ended (a busy machine) - rank 0's announcement that it now writes the outputs.
      CHECK(occurrences(output, "interrupted by SIG") ==
            1 + occurrences(output, "writing the outputs marked interrupted"));
      CHECK(occurrences(output, "a FIFO without a reader?") == 1);
    }
    CHECK_FALSE(solve.left_temporaries());
  }
  fs::remove(fifo);
}

namespace {

std::vector<nlohmann::json> monitor_lines(const std::string& path) {
  std::ifstream in(path);
  std::vector<nlohmann::json> lines;
  for (std::string line; std::getline(in, line);)
    lines.push_back(nlohmann::json::parse(line));
  // The first line is the stream's header (version, units), not an iteration.
  if (!lines.empty() && lines.front().contains("fetic_version")) lines.erase(lines.begin());
  return lines;
}

}  // namespace

// The monitor stream under mpirun: rank 0 writes the lines of the serial run (the working
// set is replicated; a full line gathers the state from every process at the same
// iterations, a collective that would hang if any process skipped it).
TEST_CASE("mpirun -np 2 fetic solve --monitor writes the serial stream, the full state gathered") {
  const std::string method = GENERATE(as<std::string>{}, "feti-c", "mprgp");
  INFO("--method " << method);
  const std::string serial = temporary("serial.jsonl"), distributed = temporary("mpi.jsonl");
  const std::string arguments = "solve " + scene("plane_pair.toml") + " --method " + method +
                                " --load-steps 0.5:1:2 --monitor-full 2 --monitor ";
  REQUIRE(run_fetic(arguments + serial).status == 0);
  const Run r = run_fetic(arguments + distributed, 2);
  INFO(r.output);
  REQUIRE(r.status == 0);
  const auto a = monitor_lines(serial), b = monitor_lines(distributed);
  REQUIRE(a.size() == b.size());
  REQUIRE(a.size() > 4);
  int full = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    INFO("line " << i << "\n" << a[i].dump() << "\n" << b[i].dump());
    CHECK(a[i]["load_factor"] == b[i]["load_factor"]);
    CHECK(a[i]["iteration"] == b[i]["iteration"]);
    CHECK(a[i]["active_set"] == b[i]["active_set"]);
    CHECK(a[i]["entered"] == b[i]["entered"]);
    CHECK(a[i]["left"] == b[i]["left"]);
    const double residual = a[i]["residual"].get<double>();
    CHECK(std::abs(b[i]["residual"].get<double>() - residual) <=
          1e-8 * std::abs(residual) + 1e-300);
    REQUIRE(a[i].contains("displacements") == b[i].contains("displacements"));
    if (!a[i].contains("displacements")) continue;
    ++full;
    double scale = 0.0, difference = 0.0;
    for (size_t s = 0; s < a[i]["displacements"].size(); ++s)
      for (size_t n = 0; n < a[i]["displacements"][s].size(); ++n)
        for (int c = 0; c < 2; ++c) {
          const double x = a[i]["displacements"][s][n][c], y = b[i]["displacements"][s][n][c];
          scale = std::max(scale, std::abs(x));
          difference = std::max(difference, std::abs(x - y));
        }
    CHECK(difference <= 1e-8 * scale);
    CHECK(a[i]["multipliers"].size() == b[i]["multipliers"].size());
  }
  CHECK(full > 1);
  fs::remove(serial);
  fs::remove(distributed);
}

TEST_CASE("under mpirun a monitor target rank 0 cannot open ends every process with status 5") {
  const std::string folder = temporary("monitor_dir");
  fs::create_directories(folder);
  const Run r = run_fetic("solve " + scene("chain.toml") + " --monitor " + folder, 2);
  INFO(r.output);
  CHECK(r.status == 5);
  CHECK(occurrences(r.output, folder) >= 1);
  fs::remove_all(folder);
}
