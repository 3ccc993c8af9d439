// The script format of `fetic gui --script`: actions become the same requests as keys and
// widgets; times are optional; every problem is reported with its line.

#include <catch2/catch.hpp>

#include "app/gui/script.hpp"

using fetic::app::gui::parse_script;
using fetic::app::gui::RequestKind;
using fetic::app::gui::ScriptError;
using namespace std::string_literals;

TEST_CASE("script lines become timed requests", "[script]") {
  std::vector<ScriptError> errors;
  const auto actions = parse_script(
      "# a demo\n"
      "load 0.5\n"
      "1.5 step   # at 1.5 s\n"
      "wait\n"
      "magnification auto\n"
      "magnification 200\n"
      "toggle stress\n"
      "screenshot out.png\n"
      "screenshot\n"
      "record-sweep 10\n"
      "2 quit\n",
      errors);
  REQUIRE(errors.empty());
  REQUIRE(actions.size() == 10);
  CHECK(actions[0].request.kind == RequestKind::SetLoad);
  CHECK(actions[0].request.value == 0.5);
  CHECK(actions[0].at < 0);
  CHECK(actions[1].request.kind == RequestKind::Step);
  CHECK(actions[1].at == 1.5);
  CHECK(actions[1].line == 3);
  CHECK(actions[2].wait);
  CHECK(actions[3].request.kind == RequestKind::SetMagnification);
  CHECK(actions[3].request.value == 0.0);
  CHECK(actions[4].request.value == 200.0);
  CHECK(actions[5].request.kind == RequestKind::Toggle);
  CHECK(actions[5].request.text == "stress");
  CHECK(actions[6].request.text == "out.png");
  CHECK(actions[7].request.text.empty());
  CHECK(actions[8].request.kind == RequestKind::RecordSweep);
  CHECK(actions[8].request.value == 10.0);
  CHECK(actions[9].request.kind == RequestKind::Quit);
  CHECK(actions[9].at == 2.0);
}

TEST_CASE("script errors name the line and the problem", "[script]") {
  std::vector<ScriptError> errors;
  parse_script("load\nload x\njump 3\ntoggle colours\n-1 quit\n1.0\nstep now\n", errors);
  REQUIRE(errors.size() == 7);
  CHECK(errors[0].line == 1);
  CHECK(errors[0].message == "'load' needs a number from 0 to 1e+300");
  CHECK(errors[1].message == "'load' needs a number from 0 to 1e+300, not 'x'");
  CHECK(errors[2].message == "unknown action 'jump'");
  CHECK(errors[3].line == 4);
  CHECK(errors[4].message == "the time must be from 0 to 3600 seconds, not '-1'");
  CHECK(errors[5].message == "a time without an action");
  CHECK(errors[6].message == "'step' takes no argument");
}

TEST_CASE("method and preconditioner names are checked, live stepping and cancel", "[script]") {
  std::vector<ScriptError> errors;
  const auto actions = parse_script(
      "method fetic\nmethod active-set\npreconditioner diriclet\npreconditioner lumped\n"
      "live on\nlive off\nlive maybe\ncancel\ncancel now\n",
      errors);
  REQUIRE(errors.size() == 4);
  CHECK(errors[0].line == 1);
  CHECK(errors[0].message == "unknown method 'fetic' (feti-c, mprgp, active-set, feti, cg or sd)");
  CHECK(errors[1].line == 3);
  CHECK(errors[1].message == "unknown preconditioner 'diriclet' (dirichlet, lumped or none)");
  CHECK(errors[2].message == "'live' needs on or off, not 'maybe'");
  CHECK(errors[3].message == "'cancel' takes no argument");
  REQUIRE(actions.size() == 5);
  CHECK(actions[0].request.kind == RequestKind::SetMethod);
  CHECK(actions[0].request.text == "active-set");
  CHECK(actions[1].request.kind == RequestKind::SetPreconditioner);
  CHECK(actions[2].request.kind == RequestKind::SetLive);
  CHECK(actions[2].request.value == 1.0);
  CHECK(actions[3].request.value == 0.0);
  CHECK(actions[4].request.kind == RequestKind::Cancel);
}

TEST_CASE("script numbers name their range", "[script]") {
  std::vector<ScriptError> errors;
  parse_script("record-sweep 1000000000\nmethod bogus\n1e308 quit\n", errors);
  REQUIRE(errors.size() == 3);
  CHECK(errors[0].message == "'record-sweep' needs a number from 2 to 10000, not '1000000000'");
  CHECK(errors[1].message == "unknown method 'bogus' (feti-c, mprgp, active-set, feti, cg or sd)");
  CHECK(errors[2].message == "the time must be from 0 to 3600 seconds, not '1e308'");
}

TEST_CASE("compare takes a method or none", "[script]") {
  std::vector<ScriptError> errors;
  const auto actions =
      parse_script("compare mprgp\ncompare none\ncompare fetic\ncompare\n", errors);
  REQUIRE(errors.size() == 2);
  CHECK(errors[0].line == 3);
  CHECK(
      errors[0].message ==
      "'compare' needs a method (feti-c, mprgp, active-set, feti, cg or sd) or none, not 'fetic'");
  CHECK(errors[1].line == 4);
  REQUIRE(actions.size() == 2);
  CHECK(actions[0].request.kind == RequestKind::SetCompare);
  CHECK(actions[0].request.text == "mprgp");
  CHECK(actions[1].request.text == "none");
}

// Issue 27, items 9 and 10: values are checked like the command line's, and quoted safely.
TEST_CASE("script values: beyond the range, control characters and a byte order mark", "[script]") {
  std::vector<ScriptError> errors;
  const auto actions = parse_script(
      "\xEF\xBB\xBFwait\nload 1e400\nmagnification 1e300\nscrub 1e10\nload 1e300\n"
      "jump\x01\nload 0x\x00\n"s,
      errors);
  REQUIRE(actions.size() == 2);  // the BOM is not part of the first action's name
  CHECK(actions[0].wait);
  CHECK(actions[0].line == 1);
  CHECK(actions[1].request.kind == RequestKind::SetLoad);  // 1e300: the scene decides (cmd_gui)
  CHECK(actions[1].request.value == 1e300);
  CHECK(actions[1].request.script_line == 5);
  REQUIRE(errors.size() == 5);
  CHECK(errors[0].message == "'load' needs a number from 0 to 1e+300, not '1e400'");
  CHECK(errors[1].message ==
        "'magnification' needs auto or a number from 1e-12 to 1e+15, not "
        "'1e300'");
  CHECK(errors[2].message == "'scrub' needs a number from 0 to 1e+09, not '1e10'");
  CHECK(errors[3].message == "unknown action 'jump\\x01'");
  CHECK(errors[4].message == "'load' needs a number from 0 to 1e+300, not '0x\\x00'");
  // A long word is quoted shortened.
  errors.clear();
  parse_script("load " + std::string(100000, '7') + "x\n", errors);
  REQUIRE(errors.size() == 1);
  CHECK(errors[0].message.size() < 200);
}
