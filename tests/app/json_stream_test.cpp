// The streamed result writer writes what scalars_first(document).dump(1) writes for the
// document with every placeholder replaced by what its maker makes.

#include <catch2/catch.hpp>

#include <cmath>
#include <functional>
#include <sstream>
#include <vector>

#include "app/json_layout.hpp"
#include "app/json_stream.hpp"
#include "app/json_text.hpp"
#include "app/result_json.hpp"
#include "scenes/load_scene.hpp"
#include "solver/method.hpp"
#include "solver/model.hpp"

using Json = nlohmann::ordered_json;

namespace {

Json strut(int index) {
  Json s;
  s["nodes"] = Json::array({Json::array({0.0, 1.5}), Json::array({2.0, -3.25e-7})});
  s["name"] = "S\"" + std::to_string(index);  // a key after a structured one, and an escape
  s["stress"] = Json::object();
  s["empty"] = Json::array();
  s["nested"] = {{"b", Json::array({1, 2, 3})}, {"a", index}};
  return s;
}

}  // namespace

TEST_CASE("A streamed document is written as the whole document's dump(1)") {
  std::vector<fetic::app::ElementMaker> makers{strut, [](int k) { return Json(k * 2); }};
  Json streamed, whole;
  for (Json* document : {&streamed, &whole}) {
    (*document)["history"] = Json::array({{{"iteration", 1}, {"residual", 0.5}}});
    (*document)["scene"] = "x.toml";
    (*document)["units"] = {{"length", "m"}};
    (*document)["load_factor"] = 1.0;
    (*document)["steps"] = Json::array();
  }
  Json struts = Json::array(), made = Json::array();
  for (int k = 0; k < 3; ++k) {
    struts.push_back(fetic::app::deferred(0, k));
    made.push_back(strut(k));
  }
  streamed["struts"] = struts;
  whole["struts"] = made;
  streamed["list"] = Json::array({fetic::app::deferred(1, 4), 7});
  whole["list"] = Json::array({8, 7});
  std::ostringstream out;
  fetic::app::write_streamed(out, streamed, makers);
  CHECK(out.str() == fetic::app::scalars_first(whole).dump(1));
  CHECK(Json::parse(out.str()) == fetic::app::scalars_first(whole));
}

// Numbers as text: JsonText against nlohmann's own dump of the same value, for the cases
// its formatting treats apart (whole doubles, the switch to exponents, -0, non-finite).
TEST_CASE("JsonText writes numbers as dump() writes them") {
  const double values[] = {0.0,    -0.0,    1.0,          100.0,    1e15,     1e16,   1.5e17,
                           1e-4,   1e-5,    -3.25e-7,     0.1,      1.0 / 3,  2.1e11, -63000.0,
                           5e-324, 1.7e308, std::nan(""), INFINITY, -INFINITY};
  for (const double value : values) {
    std::ostringstream out;
    {
      fetic::app::JsonText text(out);
      text.number(value);
    }
    CHECK(out.str() == Json(value).dump());
  }
  for (const int value : {0, -1, 7, 2147483647, -2147483647 - 1}) {
    std::ostringstream out;
    {
      fetic::app::JsonText text(out);
      text.number(value);
    }
    CHECK(out.str() == Json(value).dump());
  }
}

// Lines start from a fixed text of 64 spaces; deeper ones are indented one space at a time.
TEST_CASE("JsonText indents arrays nested deeper than its indentation text as dump(1)") {
  Json nested = 1.5;
  for (int depth = 0; depth < 70; ++depth)
    nested = Json::array({nested, depth});
  std::ostringstream out;
  {
    fetic::app::JsonText text(out);
    std::function<void(const Json&, int)> write = [&](const Json& value, int depth) {
      if (value.is_array())
        text.array(value.size(), depth, [&](size_t k, int inner) { write(value[k], inner); });
      else if (value.is_number_integer())
        text.number(value.get<int>());
      else
        text.number(value.get<double>());
    };
    write(nested, 0);
  }
  CHECK(out.str() == nested.dump(1));
}

// recurring_number keeps recent texts by the value's bits: the same text as dump() when a
// value comes again, when another value takes its place in the cache (4,000 values in a
// cache of 1,024), for -0.0 beside 0.0, and for non-finite values.
TEST_CASE("JsonText writes recurring numbers as dump() writes them") {
  std::vector<double> values = {0.0, -0.0, 1.0, 1e-5, 5e-324, std::nan(""), INFINITY, -INFINITY};
  for (int k = 0; k < 4000; ++k)
    values.push_back(0.1 * k - 1.0 / 3);
  for (int pass = 0; pass < 3; ++pass)
    for (const double value : values) {
      std::ostringstream out;
      {
        fetic::app::JsonText text(out);
        text.recurring_number(value);
      }
      CHECK(out.str() == Json(value).dump());
    }
}

// The result file of a solve with its struts written as text (write_strut) against the
// whole document built as JSON values and dumped: the same bytes, for a bar, a plane and
// a frame scene (rotations, moments), converged and torn after one FETI iteration.
TEST_CASE("A result file streamed with struts written as text is the document's dump(1)") {
  using fetic::solver::MethodKind;
  for (const char* name : {"thesis.toml", "plane_pair.toml", "frame_scaffold.toml"})
    for (const bool converged : {true, false}) {
      const fetic::scenes::Scene scene =
          fetic::scenes::load_scene_file(std::string(FETIC_BUNDLED_SCENES_DIR) + "/" + name);
      const fetic::solver::Model model = fetic::solver::build_model(scene);
      const auto method = fetic::solver::make_method(MethodKind::FetiC, model, {});
      method->start(1.0);
      if (converged)
        fetic::solver::run_to_end(*method);
      else
        method->step();
      const fetic::solver::Snapshot state = method->snapshot();
      fetic::app::RunInfo info;
      info.method = MethodKind::FetiC;
      fetic::app::StreamedParts parts;
      const Json streamed = fetic::app::result_json(model, state, method->history(), info, &parts);
      const Json whole = fetic::app::result_json(model, state, method->history(), info);
      std::ostringstream out;
      fetic::app::write_streamed(out, streamed, parts);
      INFO(name << (converged ? " converged" : " torn"));
      CHECK(parts.writers.size() == 1);
      CHECK(out.str() == fetic::app::scalars_first(whole).dump(1));
    }
}

// A long array written on the threads in runs, joined in order: the same bytes as one
// thread writes, across the runs (4,096 items) and the batches of runs (64 runs) the
// writer holds at once; nested arrays as the result file's points are.
TEST_CASE("JsonText's parallel array is written as its array") {
  const std::size_t count = 266241;  // two batches, the last run short
  std::vector<double> values(count);
  for (std::size_t k = 0; k < count; ++k)
    values[k] = std::sin(static_cast<double>(k)) * std::pow(10.0, static_cast<double>(k % 40) - 20);
  const auto write = [&](bool parallel) {
    std::ostringstream out;
    {
      fetic::app::JsonText text(out);
      text.raw("{");
      text.member("points", 1, true);
      if (parallel)
        text.parallel_array(count, 1, [&](fetic::app::JsonText& piece, std::size_t n, int at) {
          piece.array(2, at, [&](std::size_t k, int) { piece.number(values[n] + double(k)); });
        });
      else
        text.array(count, 1, [&](std::size_t n, int at) {
          text.array(2, at, [&](std::size_t k, int) { text.number(values[n] + double(k)); });
        });
      text.newline(0);
      text.raw("}");
    }
    return out.str();
  };
  const std::string serial = write(false), parallel = write(true);
  CHECK(serial.size() > 8000000);
  CHECK(parallel == serial);
  CHECK(parallel.find("\n  [\n   0.0,\n   1.0\n  ],\n  [\n") != std::string::npos);
}
