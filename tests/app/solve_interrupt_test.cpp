// `fetic solve` stopped by SIGINT or SIGTERM in the middle of a long solve: it exits 130
// and still writes its outputs - the result file, the CSV tables and the ParaView series -
// with the current iterate, marked "interrupted": true, "converged": false. The progress
// line (--progress, forced although stderr is a file here) shows the running iteration.

#include <catch2/catch.hpp>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "tests/support/child_process.hpp"

namespace fs = std::filesystem;
using namespace std::chrono_literals;

TEST_CASE("an interrupted solve writes the current iterate, marked interrupted") {
  for (const int signal : {SIGINT, SIGTERM}) {
    INFO("signal " << signal);
    const fs::path dir =
        fs::temp_directory_path() /
        ("fetic_solve_interrupt_" + std::to_string(::getpid()) + "_" + std::to_string(signal));
    fs::remove_all(dir);
    fs::create_directories(dir);
    const fs::path log = dir / "log.txt", json = dir / "result.json", csv = dir / "history.csv",
                   vtu = dir / "vtu";
    // Steepest descent on a bar of 3000 elements (condition number ~1e7): it needs far
    // more iterations than the test waits for, so it is stopped in the middle.
    const std::string scene = (dir / "long_bar.toml").string();
    std::ofstream(scene) << "model = \"bar\"\n[[strut]]\nname = \"long\"\nfrom = [0.0, 0.0]\n"
                            "to = [1.0, 0.0]\nE = 1.0e9\narea = 1.0e-4\nelements = 3000\n"
                            "fixed = [\"from\"]\n[[load]]\nstrut = \"long\"\nat = \"to\"\n"
                            "force = [1000.0, 0.0]\n";
    const pid_t child = fetic::test::start_fetic(
        {"solve", scene, "--method", "sd", "--tol", "1e-14", "--max-iterations", "1000000000",
         "--progress", "--json", json.string(), "--csv", csv.string(), "--vtu", vtu.string()},
        log);
    // Wait until the progress line reports iterations, then stop it.
    fetic::test::wait_for(
        child, [&] { return fetic::test::read_bytes(log).find("iteration") != std::string::npos; },
        60s, 20ms);
    std::this_thread::sleep_for(300ms);
    ::kill(child, signal);
    const auto status = fetic::test::wait_bounded(child, 60s);
    const std::string output = fetic::test::read_bytes(log);
    INFO(output);
    REQUIRE(status);
    REQUIRE(WIFEXITED(*status));
    CHECK(WEXITSTATUS(*status) == 130);
    CHECK_THAT(output, Catch::Contains("solve  t = 1  iteration "));
    CHECK_THAT(output, Catch::Contains("the current iterate, marked interrupted, is in"));

    std::ifstream in(json);
    REQUIRE(in.good());
    const auto result = nlohmann::json::parse(in);
    CHECK(result["interrupted"] == true);
    CHECK(result["converged"] == false);
    CHECK(result["status"] == "interrupted");
    const int iterations = result["iterations"].get<int>();
    CHECK(iterations > 0);
    CHECK(result["history"].size() == static_cast<size_t>(iterations) + 1);
    CHECK(result["struts"].size() == 1);
    // The iterate is a real one: not at rest, finite.
    double largest = 0.0;
    for (const auto& strut : result["struts"])
      for (const auto& u : strut["displacements"])
        largest = std::max(largest, std::abs(u[0].get<double>()));
    CHECK(largest > 0.0);
    CHECK(std::isfinite(largest));

    // The history table has every iteration; the ParaView series the one frame.
    std::ifstream table(csv);
    int lines = 0;
    for (std::string line; std::getline(table, line);)
      ++lines;
    CHECK(lines == iterations + 2);  // header, iterations 0..n
    CHECK(fs::exists(vtu / "struts_0000.vtu"));
    CHECK_THAT(fetic::test::read_bytes(vtu / "struts.pvd"), Catch::Contains("struts_0000.vtu"));
    for (const auto& entry : fs::recursive_directory_iterator(dir))
      CHECK(entry.path().string().find(".tmp") == std::string::npos);
    fs::remove_all(dir);
  }
}

namespace {

// Waits until `pid` runs fetic and catches SIGINT (its handler installed: /proc/PID/status,
// SigCgt), so that the signal tests fetic's handling rather than the default action at
// start-up (the forked child has the test's handlers until it runs fetic).
bool wait_for_handler(pid_t pid) {
  const auto deadline = std::chrono::steady_clock::now() + 30s;
  const fs::path fetic = fs::canonical(FETIC_EXECUTABLE);
  while (std::chrono::steady_clock::now() < deadline) {
    std::error_code error;
    const fs::path exe = fs::read_symlink("/proc/" + std::to_string(pid) + "/exe", error);
    std::ifstream status("/proc/" + std::to_string(pid) + "/status");
    if (error || exe != fetic) status.close();
    for (std::string line; std::getline(status, line);)
      if (line.rfind("SigCgt:", 0) == 0 && (std::stoull(line.substr(7), nullptr, 16) & 2u))
        return true;
    std::this_thread::sleep_for(2ms);
  }
  return false;
}

}  // namespace

TEST_CASE("interrupted at any moment of a sweep, even the set-up: 130 and only true messages") {
  // A generated scene whose set-up (the subdomain factorizations) takes a noticeable part
  // of the run; the signal comes at moments from during the set-up to within the sweep.
  // Whatever was reached: either "no outputs were written" and there are none, or the
  // outputs the message names exist, whole, and say interrupted.
  const fs::path dir =
      fs::temp_directory_path() / ("fetic_setup_interrupt_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string scene = (dir / "plane.toml").string();
  REQUIRE(std::system((std::string(FETIC_EXECUTABLE) +
                       " generate --model plane --pairs 8 --elements 120,20 --subdomains 12,4 -o " +
                       scene)
                          .c_str()) == 0);
  for (const int delay_ms : {0, 100, 400}) {
    INFO("SIGINT " << delay_ms << " ms after the handler was installed");
    const fs::path json = dir / "r.json", csv = dir / "steps.csv", vtu = dir / "vtu",
                   log = dir / "log.txt";
    fs::remove_all(json);
    fs::remove_all(csv);
    fs::remove_all(vtu);
    const pid_t child = fetic::test::start_fetic(
        {"solve", scene, "--method", "mprgp", "--load-steps", "0.5:1.5:40", "--json", json.string(),
         "--csv-steps", csv.string(), "--vtu", vtu.string()},
        log);
    REQUIRE(wait_for_handler(child));
    std::this_thread::sleep_for(std::chrono::milliseconds(delay_ms));
    ::kill(child, SIGINT);
    const auto status = fetic::test::wait_bounded(child, 60s);
    const std::string output = fetic::test::read_bytes(log);
    INFO(output);
    REQUIRE(status);
    REQUIRE(WIFEXITED(*status));
    if (WEXITSTATUS(*status) == 0) continue;  // a fast machine finished first: nothing to say
    CHECK(WEXITSTATUS(*status) == 130);
    if (output.find("no outputs were written") != std::string::npos) {
      CHECK_FALSE(fs::exists(json));
      CHECK_FALSE(fs::exists(csv));
      CHECK((!fs::exists(vtu) || fs::is_empty(vtu)));
      continue;
    }
    REQUIRE_THAT(output, Catch::Contains("marked interrupted, is in"));
    REQUIRE(fs::exists(json));
    const auto result = nlohmann::json::parse(fetic::test::read_bytes(json));
    CHECK(result["interrupted"] == true);
    CHECK(result["converged"] == false);
    CHECK(result["steps"].back()["interrupted"] == true);
    // The load-step table's last row says so too.
    const std::string table = fetic::test::read_bytes(csv);
    CHECK_THAT(table, Catch::Contains(",interrupted,"));
    CHECK(fs::exists(vtu / "struts.pvd"));
    for (const auto& entry : fs::recursive_directory_iterator(dir))
      CHECK(entry.path().string().find(".tmp") == std::string::npos);
  }
  fs::remove_all(dir);
}
