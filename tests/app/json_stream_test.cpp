// The streamed result writer writes what scalars_first(document).dump(1) writes for the
// document with every placeholder replaced by what its maker makes.

#include <catch2/catch.hpp>

#include <sstream>

#include "app/json_layout.hpp"
#include "app/json_stream.hpp"

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
