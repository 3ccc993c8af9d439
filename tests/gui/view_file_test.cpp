// Saved views (app/view_file.hpp): what is written is read back; every bad entry is
// refused naming the file and the entry; the script actions that use them.

#include <catch2/catch.hpp>

#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "app/gui/script.hpp"
#include "app/json_input.hpp"
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
  view.corners = true;
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
  CHECK(back.corners == true);
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
  CHECK(applied.show_corners);

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
  CHECK_THAT(error_of(R"({"zoom": -1})"),
             Catch::Contains("'zoom' must be from 0.01 to 1000, not -1"));
  CHECK_THAT(error_of(R"({"zoom": "big"})"), Catch::Contains("'zoom' must be from 0.01"));
  CHECK_THAT(error_of(R"({"size": [10, 800]})"),
             Catch::Contains("'size[0]' must be a whole number of pixels from 16 to 8192, not 10"));
  CHECK_THAT(error_of(R"({"color": "blue"})"), Catch::Contains("'color' must be"));
  CHECK_THAT(error_of(R"({"color": "blue"})"), Catch::Contains(R"("moment")"));
  CHECK_THAT(error_of(R"({"center": [1]})"), Catch::Contains("'center' must be [x, y]"));
  CHECK_THAT(error_of(R"({"zom": 2})"), Catch::Contains("unknown entry 'zom'"));
  CHECK_THAT(error_of(R"({"show": {"force": true}})"),
             Catch::Contains("unknown entry 'force' in 'show'"));
  CHECK_THAT(error_of(R"({"show": {"forces": 1}})"),
             Catch::Contains("'forces' must be true or false"));
  CHECK_THROWS_WITH(fetic::app::read_view_file("/nonexistent/view.json"),
                    Catch::Contains("/nonexistent/view.json: cannot open the view file"));
}

// Issue 27, items 1 and 10: what used to abort (SIGABRT) or pass unchecked.
TEST_CASE("numbers beyond the double range are refused naming the entry and its range") {
  CHECK_THAT(error_of(R"({"zoom": 1e400})"),
             Catch::Contains(":1: 'zoom' is 1e400, beyond the range of a number") &&
                 Catch::Contains("it must be from 0.01 to 1000"));
  CHECK_THAT(error_of("{\n\"magnification\": -1e999}"),
             Catch::Contains(":2: 'magnification' is -1e999") &&
                 Catch::Contains("\"auto\" or a number from 1e-12 to 1e15"));
  CHECK_THAT(error_of(R"({"center": [1e999, 0]})"),
             Catch::Contains("'center[0]' is 1e999") && Catch::Contains("from -1e15 to 1e15"));
  CHECK_THAT(error_of(R"({"center": [0, 1e999]})"), Catch::Contains("'center[1]' is 1e999"));
  CHECK_THAT(error_of(R"({"scales": {"lateral": [1, 2, 1e400]}})"),
             Catch::Contains("'scales.lateral[2]' is 1e400"));
  // 100,000 digits: quoted shortened, the message stays one readable line.
  const std::string digits(100000, '9');
  const std::string long_number = error_of("{\"zoom\": " + digits + "}");
  CHECK_THAT(long_number, Catch::Contains("'zoom' is 999") && Catch::Contains("(100000 bytes)"));
  CHECK(long_number.size() < 300);
  // In range for a double but not for the entry.
  CHECK_THAT(error_of(R"({"size": [16384, 16384]})"),
             Catch::Contains("'size[0]' must be a whole number of pixels from 16 to 8192"));
  CHECK_THAT(error_of(R"({"size": [800.5, 600]})"), Catch::Contains("'size[0]' must be"));
  CHECK_THAT(error_of(R"({"scales": {"iterations": 1e300}})"),
             Catch::Contains("'scales.iterations' must be a whole number from 0 to 1e9"));
  CHECK_THAT(error_of(R"({"fetic_view": "1"})"),
             Catch::Contains("'fetic_view' must be 1 (the format's version), not \"1\""));
  CHECK_THAT(error_of(R"({"fetic_view": 2})"), Catch::Contains("'fetic_view' must be 1"));
  CHECK_THAT(error_of(std::string(20, '[') + std::string(20, ']')),
             Catch::Contains("nests deeper than 16 levels"));
}

TEST_CASE("a view file is read like every input: folders and devices refused, a size limit") {
  const auto folder =
      std::filesystem::temp_directory_path() / ("fetic_view_folder_" + std::to_string(::getpid()));
  std::filesystem::create_directories(folder);
  CHECK_THROWS_WITH(fetic::app::read_view_file(folder.string()),
                    Catch::EndsWith(": is a folder, not a view file"));
  CHECK_THROWS_WITH(fetic::app::read_view_file("/dev/zero"),
                    Catch::EndsWith("/dev/zero: is a device, not a view file"));
  std::filesystem::remove(folder);
  // Over the limit: refused before it is read.
  const std::string big = file_with(std::string(fetic::app::kMaxInputFileBytes + 1, ' '));
  CHECK_THROWS_WITH(fetic::app::read_view_file(big),
                    Catch::Contains("the limit for a view file is 8.0 MiB"));
}

TEST_CASE("a saved view says \"auto\" for an automatic magnification and reads it back") {
  fetic::app::SavedView view;
  view.magnification = 0.0;
  const std::string text = fetic::app::view_json(view);
  CHECK_THAT(text, Catch::Contains(R"("magnification": "auto")"));
  CHECK(fetic::app::read_view_file(file_with(text)).magnification == 0.0);
  CHECK(fetic::app::read_view_file(file_with(R"({"magnification": 0.0})")).magnification == 0.0);
  CHECK(fetic::app::read_view_file(file_with(R"({"magnification": 150})")).magnification == 150);
  CHECK_THAT(error_of(R"({"magnification": "big"})"), Catch::Contains("'magnification' must be"));
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
  fetic::app::gui::parse_script(
      "view\nlocate pair\nlocate node:1\nlocate pair:1:2\nlocate pair:abc\nlocate pair:-1\n"
      "locate node:1:2x\nlocate pair:99999999999999999999999999999\n",
      errors);
  REQUIRE(errors.size() == 8);
  CHECK(errors[0].message == "'view' needs a view file");
  CHECK(errors[1].message == "'locate' needs pair:K or node:STRUT:N, not 'pair'");
  CHECK(errors[4].message == "'locate' needs pair:K or node:STRUT:N, not 'pair:abc'");
  CHECK(errors[5].line == 6);
  CHECK(errors[6].line == 7);
  CHECK(errors[7].line == 8);
}
