// Saved views (app/view_file.hpp): what is written is read back; every bad entry is
// refused naming the file and the entry; the script actions that use them.

#include <catch2/catch.hpp>

#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "app/gui/script.hpp"
#include "app/view_file.hpp"

namespace {

std::string file_with(const std::string& text) {
  const auto path = std::filesystem::temp_directory_path() /
                    ("fetic_view_test_" + std::to_string(::getpid()) + ".json");
  std::ofstream(path) << text;
  return path.string();
}

std::string error_of(const std::string& text) {
  try {
    fetic::app::read_view_file(file_with(text));
  } catch (const fetic::app::ViewFileError& error) {
    return error.what();
  }
  return "";
}

}  // namespace

TEST_CASE("a saved view is read back as written") {
  fetic::app::SavedView view;
  view.width = 950;
  view.height = 800;
  view.center_x = 1.25;
  view.center_y = -0.5;
  view.zoom = 2.5;
  view.magnification = 200.0;
  view.color_by = fetic::render::ColorBy::Strut;
  view.forces = false;
  view.gaps = true;
  view.overlay = false;
  fetic::render::RunExtent scales;
  scales.largest_displacement = 0.002;
  scales.largest_force = 1.5e5;
  scales.largest_stress = 3e8;
  scales.largest_iteration = 12;
  scales.largest_active_set = 27;
  scales.smallest_residual = 1e-11;
  scales.largest_residual = 0.4;
  view.scales = scales;
  const std::string path = file_with(fetic::app::view_json(view));
  const fetic::app::SavedView back = fetic::app::read_view_file(path);
  CHECK(back.width == 950);
  CHECK(back.height == 800);
  CHECK(back.center_x == 1.25);
  CHECK(back.center_y == -0.5);
  CHECK(back.zoom == 2.5);
  CHECK(back.magnification == 200.0);
  CHECK(back.color_by == fetic::render::ColorBy::Strut);
  CHECK(back.forces == false);
  CHECK(back.gaps == true);
  CHECK(back.overlay == false);
  REQUIRE(back.scales);
  CHECK(back.scales->largest_stress == 3e8);
  CHECK(back.scales->largest_iteration == 12);
  CHECK(back.scales->smallest_residual == 1e-11);

  fetic::render::View applied;
  fetic::app::apply_view(back, applied);
  CHECK(applied.width == 950);
  CHECK(applied.zoom == 2.5);
  CHECK(applied.centered);
  CHECK(applied.center_x == 1.25);
  CHECK_FALSE(applied.show_forces);

  // A partial view changes only what it names.
  const fetic::app::SavedView partial = fetic::app::read_view_file(file_with(R"({"zoom": 2})"));
  fetic::render::View kept;
  fetic::app::apply_view(partial, kept);
  CHECK(kept.zoom == 2.0);
  CHECK(kept.width == fetic::render::View{}.width);
  CHECK_FALSE(kept.centered);
}

TEST_CASE("a view coloured by bending moment is read back with its moment scale") {
  fetic::app::SavedView view;
  view.color_by = fetic::render::ColorBy::Moment;
  fetic::render::RunExtent scales;
  scales.largest_moment = 3.27e4;
  view.scales = scales;
  const std::string text = fetic::app::view_json(view);
  CHECK_THAT(text, Catch::Contains(R"("color": "moment")"));
  CHECK_THAT(text, Catch::Contains(R"("moment": 32700)"));
  const fetic::app::SavedView back = fetic::app::read_view_file(file_with(text));
  CHECK(back.color_by == fetic::render::ColorBy::Moment);
  REQUIRE(back.scales);
  CHECK(back.scales->largest_moment == 3.27e4);
  fetic::render::View applied;
  fetic::app::apply_view(back, applied);
  CHECK(applied.color_by == fetic::render::ColorBy::Moment);
  fetic::render::RunExtent extent;
  fetic::app::apply_scales(back.scales, extent);
  CHECK(extent.largest_moment == 3.27e4);
  // Written by hand, too; every colouring's name is its own.
  CHECK(fetic::app::read_view_file(file_with(R"({"color": "moment"})")).color_by ==
        fetic::render::ColorBy::Moment);
  for (const auto color : {fetic::render::ColorBy::Subdomain, fetic::render::ColorBy::Stress,
                           fetic::render::ColorBy::Strut, fetic::render::ColorBy::Moment})
    CHECK(fetic::app::color_from_name(fetic::app::color_name(color)) == color);
  CHECK_FALSE(fetic::app::color_from_name("moments"));
}

TEST_CASE("scripts choose the colouring: color NAME, toggle moment") {
  std::vector<fetic::app::gui::ScriptError> errors;
  const auto actions = fetic::app::gui::parse_script(
      "color moment\ncolor strut\ntoggle moment\ntoggle stress\n", errors);
  REQUIRE(errors.empty());
  REQUIRE(actions.size() == 4);
  CHECK(actions[0].request.kind == fetic::app::gui::RequestKind::SetColor);
  CHECK(actions[0].request.text == "moment");
  CHECK(actions[1].request.text == "strut");
  CHECK(actions[2].request.kind == fetic::app::gui::RequestKind::Toggle);
  CHECK(actions[2].request.text == "moment");
  CHECK(actions[3].request.text == "stress");
  fetic::app::gui::parse_script("color blue\n", errors);
  REQUIRE(errors.size() == 1);
  CHECK_THAT(errors[0].message,
             Catch::Contains("'color' needs subdomain, strut, stress or moment"));
}

TEST_CASE("a bad view file is refused naming the entry") {
  CHECK_THAT(error_of("{\"zoom\": 2,\n \"size\": [1, }"),
             Catch::Contains(":2: not a JSON view file"));
  CHECK_THAT(error_of("[1, 2]"), Catch::Contains("a view file is a JSON object"));
  CHECK_THAT(error_of(R"({"zoom": -1})"), Catch::Contains("'zoom' must be a positive number"));
  CHECK_THAT(error_of(R"({"zoom": "big"})"), Catch::Contains("'zoom' must be a number"));
  CHECK_THAT(error_of(R"({"size": [10, 800]})"), Catch::Contains("'size' must be [width, height]"));
  CHECK_THAT(error_of(R"({"color": "blue"})"), Catch::Contains("'color' must be"));
  CHECK_THAT(error_of(R"({"color": "blue"})"), Catch::Contains(R"("moment")"));
  CHECK_THAT(error_of(R"({"center": [1]})"), Catch::Contains("'center' must be [x, y]"));
  CHECK_THAT(error_of(R"({"zom": 2})"), Catch::Contains("unknown entry 'zom'"));
  CHECK_THAT(error_of(R"({"show": {"force": true}})"),
             Catch::Contains("unknown entry 'force' in 'show'"));
  CHECK_THAT(error_of(R"({"show": {"forces": 1}})"),
             Catch::Contains("'forces' must be true or false"));
  CHECK_THROWS_WITH(fetic::app::read_view_file("/nonexistent/view.json"),
                    Catch::Contains("/nonexistent/view.json: cannot read the view file"));
}

TEST_CASE("scripts load and save views and locate items") {
  std::vector<fetic::app::gui::ScriptError> errors;
  const auto actions = fetic::app::gui::parse_script(
      "view a.json\nsave-view\nsave-view b.json\nlocate pair:3\nlocate node:0:44\n"
      "screenshot-window\n",
      errors);
  REQUIRE(errors.empty());
  REQUIRE(actions.size() == 6);
  CHECK(actions[0].request.kind == fetic::app::gui::RequestKind::LoadView);
  CHECK(actions[0].request.text == "a.json");
  CHECK(actions[1].request.kind == fetic::app::gui::RequestKind::SaveView);
  CHECK(actions[2].request.text == "b.json");
  CHECK(actions[3].request.kind == fetic::app::gui::RequestKind::Locate);
  CHECK(actions[4].request.text == "node:0:44");
  CHECK(actions[5].request.kind == fetic::app::gui::RequestKind::ScreenshotWindow);
  fetic::app::gui::parse_script("view\nlocate pair\nlocate node:1\nlocate pair:1:2\n", errors);
  REQUIRE(errors.size() == 4);
  CHECK(errors[0].message == "'view' needs a view file");
  CHECK(errors[1].message == "'locate' needs pair:K or node:STRUT:N");
}
