// The window's keys and mouse gestures (app/gui/bindings.hpp): the help overlay is made
// from the table the key handler uses, and docs/WINDOW.md's key table lists every key.

#include <catch2/catch.hpp>

#include <fstream>
#include <iterator>
#include <set>
#include <string>

#include "app/gui/bindings.hpp"

using fetic::app::gui::help_rows;
using fetic::app::gui::key_bindings;
using fetic::app::gui::mouse_bindings;

TEST_CASE("the help lists every key and mouse gesture the window handles", "[script]") {
  const auto rows = help_rows();
  std::string help;
  for (const auto& [keys, does] : rows)
    help += keys + " | " + does + "\n";
  std::set<int> keys;
  for (const auto& binding : key_bindings()) {
    CHECK(keys.insert(binding.key).second);  // one meaning per key
    CHECK_THAT(help, Catch::Contains(binding.name) && Catch::Contains(binding.does));
  }
  for (const auto& gesture : mouse_bindings())
    CHECK_THAT(help,
               Catch::Contains(std::string("mouse ") + gesture.gesture + " | " + gesture.does));
  // Keys with one meaning share a row; V (save view), W (window screenshot) and a click
  // (pin) are listed - the ones the first overlay left out.
  CHECK_THAT(help, Catch::Contains("H, F1 | this help") && Catch::Contains("Q, Esc | quit"));
  CHECK_THAT(help, Catch::Contains("V | save the view") && Catch::Contains("W | screenshot") &&
                       Catch::Contains("mouse click | pin"));
}

TEST_CASE("docs/WINDOW.md's key table names every key", "[script]") {
  std::ifstream in(std::string(FETIC_BUNDLED_SCENES_DIR) + "/../docs/WINDOW.md");
  REQUIRE(in);
  const std::string doc{std::istreambuf_iterator<char>(in), {}};
  for (const auto& binding : key_bindings())
    CHECK_THAT(doc, Catch::Contains(std::string("| ") + binding.name) ||
                        Catch::Contains(std::string(", ") + binding.name + " |"));
}
