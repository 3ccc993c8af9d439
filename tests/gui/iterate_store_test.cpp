// The window's store of a solve's iterates: within its budget it keeps the first, the
// newest and evenly spaced ones between, and every entry shows the nearest kept iterate
// at or before it.

#include <catch2/catch.hpp>

#include <memory>
#include <set>

#include "app/gui/iterate_store.hpp"

using fetic::app::gui::append_iterate;
using fetic::app::gui::Iterates;

namespace {

std::shared_ptr<const fetic::solver::Snapshot> iterate(int iteration) {
  auto s = std::make_shared<fetic::solver::Snapshot>();
  s->iteration = iteration;
  return s;
}

}  // namespace

TEST_CASE("the window keeps every iterate of a solve within its budget") {
  Iterates iterates;
  for (int k = 0; k < 40; ++k)
    append_iterate(iterates, iterate(k), 100);
  REQUIRE(iterates.size() == 40);
  for (int k = 0; k < 40; ++k)
    CHECK(iterates[static_cast<std::size_t>(k)]->iteration == k);
}

TEST_CASE("beyond its budget the window keeps the first, the newest and evenly spaced ones") {
  for (const std::size_t keep : {3u, 4u, 7u, 16u}) {
    Iterates iterates;
    for (int k = 0; k < 300; ++k) {
      append_iterate(iterates, iterate(k), keep);
      REQUIRE(iterates.size() == static_cast<std::size_t>(k) + 1);
      std::set<const fetic::solver::Snapshot*> distinct;
      int previous = -1;
      for (int i = 0; i <= k; ++i) {
        const auto& shown = iterates[static_cast<std::size_t>(i)];
        distinct.insert(shown.get());
        CHECK(shown->iteration <= i);         // never a later iterate
        CHECK(shown->iteration >= previous);  // scrubbing forward never goes back
        previous = shown->iteration;
      }
      CHECK(iterates.front()->iteration == 0);
      CHECK(iterates.back()->iteration == k);
      CHECK(distinct.size() <= keep);
      // Not thinned more than needed: at least half the budget stays in use.
      CHECK(distinct.size() >=
            std::min<std::size_t>(keep / 2 + 1, static_cast<std::size_t>(k) + 1));
    }
  }
}

TEST_CASE("the iterate budget counts a snapshot's values") {
  fetic::solver::Snapshot s;
  s.pieces.resize(2);
  s.pieces[0].displacement.resize(1000);
  s.pieces[1].displacement.resize(3000);
  s.dual.resize(500);
  const std::size_t bytes = fetic::app::gui::snapshot_bytes(s);
  CHECK(bytes >= 4000 * sizeof(fetic::solver::Vec2) + 500 * sizeof(double));
  CHECK(bytes < 4000 * sizeof(fetic::solver::Vec2) + 500 * sizeof(double) + 4096);
  CHECK(fetic::app::gui::iterates_within(s, 10 * bytes) == 10);
  CHECK(fetic::app::gui::iterates_within(s, bytes) == 3);
}
