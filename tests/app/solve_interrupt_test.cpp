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
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <string>
#include <thread>

#include <nlohmann/json.hpp>

namespace fs = std::filesystem;
using namespace std::chrono_literals;

namespace {

std::string read_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

std::optional<int> wait_bounded(pid_t child, std::chrono::seconds limit) {
  const auto deadline = std::chrono::steady_clock::now() + limit;
  int status = 0;
  while (std::chrono::steady_clock::now() < deadline) {
    if (::waitpid(child, &status, WNOHANG) == child) return status;
    std::this_thread::sleep_for(10ms);
  }
  ::kill(child, SIGKILL);
  ::waitpid(child, &status, 0);
  return std::nullopt;
}

}  // namespace

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
    const pid_t child = ::fork();
    if (child == 0) {
      std::FILE* file = std::fopen(log.c_str(), "w");
      if (file) {
        ::dup2(::fileno(file), 1);
        ::dup2(::fileno(file), 2);
      }
      ::execl(FETIC_EXECUTABLE, "fetic", "solve", scene.c_str(), "--method", "sd", "--tol", "1e-14",
              "--max-iterations", "1000000000", "--progress", "--json", json.c_str(), "--csv",
              csv.c_str(), "--vtu", vtu.c_str(), static_cast<char*>(nullptr));
      ::_exit(127);
    }
    // Wait until the progress line reports iterations, then stop it.
    const auto deadline = std::chrono::steady_clock::now() + 60s;
    while (read_text(log).find("iteration") == std::string::npos &&
           std::chrono::steady_clock::now() < deadline)
      std::this_thread::sleep_for(20ms);
    std::this_thread::sleep_for(300ms);
    ::kill(child, signal);
    const auto status = wait_bounded(child, 60s);
    const std::string output = read_text(log);
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
    CHECK_THAT(read_text(vtu / "struts.pvd"), Catch::Contains("struts_0000.vtu"));
    for (const auto& entry : fs::recursive_directory_iterator(dir))
      CHECK(entry.path().string().find(".tmp") == std::string::npos);
    fs::remove_all(dir);
  }
}
