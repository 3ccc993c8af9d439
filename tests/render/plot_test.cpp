// Plots: tick positions and labels, ranges, and the data-to-pixel map.

#include <catch2/catch.hpp>

#include <cmath>

#include "render/plot.hpp"

using namespace fetic::render;

TEST_CASE("linear ticks step by 1, 2 or 5 times a power of ten and label without noise") {
  const auto ticks = linear_ticks(0.0, 1.0, 5, false);
  REQUIRE(ticks.size() == 6);
  CHECK(ticks[1].value == Approx(0.2));
  CHECK(ticks[1].label == "0.2");
  CHECK(ticks[0].label == "0");
  const auto negative = linear_ticks(-3.0, 3.0, 6, false);
  CHECK(negative.front().label == "-3");
  const auto counts = linear_ticks(0.0, 3.0, 10, true);  // never half an iteration
  for (const Tick& tick : counts)
    CHECK(tick.value == std::round(tick.value));
  CHECK(counts.size() == 4);
}

TEST_CASE("log ticks sit on powers of ten and thin out over many decades") {
  const auto few = log_ticks(1e-3, 1e0, 6);
  int majors = 0;
  for (const Tick& tick : few)
    majors += tick.major ? 1 : 0;
  CHECK(majors == 4);
  CHECK(few.front().label == "10⁻³");
  const auto many = log_ticks(1e-16, 1e0, 5);
  for (const Tick& tick : many)
    CHECK(tick.major);  // no minor ticks over 16 decades
  CHECK(many.size() <= 6);
}

TEST_CASE("ranges round out to the tick grid, log ranges to whole decades") {
  double low = 0, high = 0;
  nice_range(Axis{}, low, high, {0.13, 0.87});
  CHECK(low == Approx(0.0));
  CHECK(high == Approx(1.0));
  Axis log_axis;
  log_axis.log = true;
  nice_range(log_axis, low, high, {3e-11, 0.5, -1.0, 0.0});  // non-positive values ignored
  CHECK(low == Approx(1e-11));
  CHECK(high == Approx(1.0));
}

TEST_CASE("the plot area maps data to pixels, y up, log where asked") {
  const PlotArea area({100, 50, 300, 250}, 0.0, 10.0, 1e-4, 1.0, false, true);
  CHECK(area.to_pixel(0.0, 1e-4).x == Approx(100.0f));
  CHECK(area.to_pixel(0.0, 1e-4).y == Approx(250.0f));
  CHECK(area.to_pixel(10.0, 1.0).y == Approx(50.0f));
  CHECK(area.to_pixel(5.0, 1e-2).y == Approx(150.0f));
}

TEST_CASE("a plot keeps its series inside the frame and labels its axes") {
  PlotSpec spec;
  spec.frame = {0, 0, 400, 300};
  spec.title = "residual";
  spec.x.label = "iteration";
  spec.y.label = "‖w‖";
  spec.y.log = true;
  spec.y.max = 1.0;  // data above it must be clipped, not drawn outside
  spec.series.push_back({"FETI-C", {0, 1, 2, 3}, {10.0, 1e-2, 1e-5, 1e-9}, {0, 0, 255, 255}});
  const DrawList list = draw_plot(spec);
  for (const Vertex& v : list.vertices()) {
    CHECK(v.position.x >= -1.0f);
    CHECK(v.position.x <= 401.0f);
    CHECK(v.position.y >= -1.0f);
    CHECK(v.position.y <= 301.0f);
  }
  bool title = false, x_label = false, y_label = false, legend = false;
  for (const TextItem& text : list.texts()) {
    title = title || text.text == "residual";
    x_label = x_label || text.text == "iteration";
    y_label = y_label || (text.text == "‖w‖" && text.vertical);
    legend = legend || text.text == "FETI-C";
  }
  CHECK(title);
  CHECK(x_label);
  CHECK(y_label);
  CHECK(legend);
}
