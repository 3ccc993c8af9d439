// The ParaView series of a load sweep: each frame's entry is appended to the .pvd files
// in place (linear in the frames), which stay complete, in order, after every frame.

#include <catch2/catch.hpp>

#include <cstdio>
#include <filesystem>
#include <string>

#include "tests/support/process.hpp"

namespace {

using fetic::test::read_text;
using fetic::test::run_fetic;
using fetic::test::TempDir;

}  // namespace

TEST_CASE("a sweep's .pvd files list every frame once, in order, and end closed") {
  TempDir dir;
  const auto run = run_fetic({"solve", fetic::test::bundled_scene("two_bars.toml"), "--quiet",
                              "--load-steps", "0:2:41", "--vtu", dir / "vtu"});
  INFO(run.err);
  REQUIRE(run.status == 0);
  for (const std::string dataset : {"struts", "contacts"}) {
    const std::string pvd = read_text(dir / ("vtu/" + dataset + ".pvd"));
    INFO(pvd);
    size_t at = 0;
    for (int k = 0; k <= 40; ++k) {
      char name[64];
      std::snprintf(name, sizeof name, "file=\"%s_%04d.vtu\"", dataset.c_str(), k);
      const size_t found = pvd.find(name, at);
      REQUIRE(found != std::string::npos);
      CHECK(std::filesystem::exists(dir /
                                    ("vtu/" + std::string(name).substr(6, dataset.size() + 9))));
      at = found + 1;
    }
    CHECK(pvd.find("_0041.vtu") == std::string::npos);
    size_t entries = 0;
    for (size_t p = pvd.find("<DataSet"); p != std::string::npos; p = pvd.find("<DataSet", p + 1))
      ++entries;
    CHECK(entries == 41);
    CHECK(pvd.size() > 40);
    CHECK(pvd.substr(pvd.size() - 27) == "  </Collection>\n</VTKFile>\n");
    CHECK(pvd.rfind("<?xml", 0) == 0);
  }
}
