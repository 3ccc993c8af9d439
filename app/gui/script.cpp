#include "app/gui/script.hpp"

#include <charconv>
#include <cstdio>
#include <sstream>
#include <string_view>
#include <vector>

#include "app/json_input.hpp"
#include "app/parse_number.hpp"
#include "solver/method.hpp"

namespace fetic::app::gui {
namespace {

constexpr int kMaxScriptSeconds = 3600;

std::string short_number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", value);
  return text;
}

// What an action takes after its name.
enum class Argument {
  None,      // play, pause, ...
  Number,    // load 0.5: a finite number within [low, high] (the command line's parser)
  Choice,    // toggle forces: one of `choices` (or what `known` accepts)
  Optional,  // screenshot [FILE]
  Required,  // view FILE
  Locate,    // pair:K | node:STRUT:N
};

struct ActionSpec {
  const char* verb;
  RequestKind kind;
  Argument argument;
  double low = 0.0, high = 0.0;                 // Number
  const char* choices = nullptr;                // Choice: "a, b or c", for the message
  bool (*known)(const std::string&) = nullptr;  // Choice: accepted names
};

bool is_method(const std::string& name) {
  return solver::parse_method(name).has_value();
}
bool is_preconditioner(const std::string& name) {
  return solver::parse_preconditioner(name).has_value();
}
bool is_compare(const std::string& name) {
  return name == "none" || is_method(name);
}
bool is_on_off(const std::string& name) {
  return name == "on" || name == "off";
}
bool is_toggle(const std::string& name) {
  for (const char* t : {"subdomains", "forces", "gaps", "stress", "moment", "overlay", "labels",
                        "chart", "corners", "help"})
    if (name == t) return true;
  return false;
}
bool is_color(const std::string& name) {
  return name == "subdomain" || name == "strut" || name == "stress" || name == "moment";
}

// Every action of the script format (docs/WINDOW.md lists the same), by the argument it
// takes: a number in a range, a name from a list, nothing, a file or a place.
const ActionSpec kActions[] = {
    {"load", RequestKind::SetLoad, Argument::Number, 0.0, 1e300},
    {"magnification", RequestKind::SetMagnification, Argument::Number, 1e-12, 1e15},
    {"scrub", RequestKind::Scrub, Argument::Number, 0.0, 1e9},
    {"record-sweep", RequestKind::RecordSweep, Argument::Number, 2.0, 10000.0},

    {"method", RequestKind::SetMethod, Argument::Choice, 0, 0,
     "feti-c, mprgp, feti-dp, active-set, feti, cg or sd", &is_method},
    {"preconditioner", RequestKind::SetPreconditioner, Argument::Choice, 0, 0,
     "dirichlet, lumped or none", &is_preconditioner},
    {"compare", RequestKind::SetCompare, Argument::Choice, 0, 0,
     "a method (feti-c, mprgp, feti-dp, active-set, feti, cg or sd) or none", &is_compare},
    {"live", RequestKind::SetLive, Argument::Choice, 0, 0, "on or off", &is_on_off},
    {"toggle", RequestKind::Toggle, Argument::Choice, 0, 0,
     "subdomains, forces, gaps, stress, moment, overlay, labels, chart, corners or help",
     &is_toggle},
    {"color", RequestKind::SetColor, Argument::Choice, 0, 0, "subdomain, strut, stress or moment",
     &is_color},

    {"play", RequestKind::Play, Argument::None},
    {"pause", RequestKind::Pause, Argument::None},
    {"step", RequestKind::Step, Argument::None},
    {"back", RequestKind::StepBack, Argument::None},
    {"reset", RequestKind::Reset, Argument::None},
    {"cancel", RequestKind::Cancel, Argument::None},
    {"record-iterations", RequestKind::RecordIterations, Argument::None},
    {"reload", RequestKind::Reload, Argument::None},
    {"wait", RequestKind::Quit, Argument::None},
    {"quit", RequestKind::Quit, Argument::None},

    {"screenshot", RequestKind::Screenshot, Argument::Optional},
    {"screenshot-window", RequestKind::ScreenshotWindow, Argument::Optional},
    {"save-view", RequestKind::SaveView, Argument::Optional},
    {"export-vtu", RequestKind::ExportParaView, Argument::Optional},
    {"view", RequestKind::LoadView, Argument::Required},
    {"locate", RequestKind::Locate, Argument::Locate},
};

// A whole number that fits (from_chars: no sign, no spaces, no overflow).
bool whole_number(std::string_view text) {
  long value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  return error == std::errc() && end == text.data() + text.size() && value >= 0;
}

// "pair:K" or "node:STRUT:N", K, STRUT, N whole numbers.
bool locate_target(const std::string& text) {
  std::vector<std::string_view> parts;
  std::string_view rest = text;
  for (std::size_t colon; (colon = rest.find(':')) != std::string_view::npos;) {
    parts.push_back(rest.substr(0, colon));
    rest.remove_prefix(colon + 1);
  }
  parts.push_back(rest);
  if (parts[0] == "pair") return parts.size() == 2 && whole_number(parts[1]);
  if (parts[0] == "node")
    return parts.size() == 3 && whole_number(parts[1]) && whole_number(parts[2]);
  return false;
}

// The argument checked against the action's kind; "" when it fits, else the problem.
std::string argument_problem(const ActionSpec& spec, const std::string& verb,
                             const std::string& argument, Request& r) {
  const std::string got = argument.empty() ? "" : ", not '" + quoted_value(argument) + "'";
  switch (spec.argument) {
    case Argument::None:
      return argument.empty() ? "" : "'" + verb + "' takes no argument";
    case Argument::Number: {
      if (spec.kind == RequestKind::SetMagnification && argument == "auto") {
        r.value = 0.0;
        return "";
      }
      const auto value = parse_number(argument);
      if (!value || *value < spec.low || *value > spec.high)
        return "'" + verb + "' needs " +
               (spec.kind == RequestKind::SetMagnification ? "auto or " : "") + "a number from " +
               short_number(spec.low) + " to " + short_number(spec.high) + got;
      r.value = *value;
      return "";
    }
    case Argument::Choice:
      if (!spec.known(argument)) {
        if (argument.empty()) return "'" + verb + "' needs " + spec.choices;
        if (spec.kind == RequestKind::SetMethod || spec.kind == RequestKind::SetPreconditioner)
          return "unknown " + verb + " '" + quoted_value(argument) + "' (" + spec.choices + ")";
        return "'" + verb + "' needs " + spec.choices + got;
      }
      r.text = argument;
      r.value = argument == "on" ? 1.0 : 0.0;
      return "";
    case Argument::Optional:
      r.text = argument;
      return "";
    case Argument::Required:
      r.text = argument;
      return argument.empty() ? "'" + verb + "' needs a view file" : "";
    case Argument::Locate:
      r.text = argument;
      return locate_target(argument) ? "" : "'locate' needs pair:K or node:STRUT:N" + got;
  }
  return "";
}

}  // namespace

std::vector<ScriptAction> parse_script(const std::string& text, std::vector<ScriptError>& errors) {
  std::vector<ScriptAction> actions;
  // A byte order mark some editors put first is not part of the first action.
  std::istringstream in(text.rfind("\xEF\xBB\xBF", 0) == 0 ? text.substr(3) : text);
  std::string raw;
  int line = 0;
  while (std::getline(in, raw)) {
    ++line;
    if (const auto hash = raw.find('#'); hash != std::string::npos) raw.resize(hash);
    std::istringstream words(raw);
    std::vector<std::string> w;
    for (std::string word; words >> word;)
      w.push_back(word);
    if (w.empty()) continue;
    ScriptAction action;
    action.line = line;
    action.request.script_line = line;
    std::size_t i = 0;
    if (const auto time = parse_number(w[0])) {
      // A script is a demo or a test: an hour is plenty, and a time like 1e308 would
      // keep the window open for ever.
      if (!(*time >= 0 && *time <= kMaxScriptSeconds)) {
        errors.push_back({line, "the time must be from 0 to " + std::to_string(kMaxScriptSeconds) +
                                    " seconds, not '" + quoted_value(w[0]) + "'"});
        continue;
      }
      action.at = *time;
      ++i;
    }
    if (i >= w.size()) {
      errors.push_back({line, "a time without an action"});
      continue;
    }
    const std::string& verb = w[i];
    const std::string argument = i + 1 < w.size() ? w[i + 1] : "";
    const ActionSpec* spec = nullptr;
    for (const ActionSpec& s : kActions)
      if (verb == s.verb) spec = &s;
    if (!spec) {
      errors.push_back({line, "unknown action '" + quoted_value(verb) + "'"});
      continue;
    }
    if (i + 2 < w.size()) {
      errors.push_back({line, "too many words after '" + verb + "'"});
      continue;
    }
    action.request.kind = spec->kind;
    action.wait = verb == "wait";
    if (const std::string problem = argument_problem(*spec, verb, argument, action.request);
        !problem.empty()) {
      errors.push_back({line, problem});
      continue;
    }
    actions.push_back(action);
  }
  return actions;
}

}  // namespace fetic::app::gui
