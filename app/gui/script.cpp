#include "app/gui/script.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>

#include "solver/method.hpp"

namespace fetic::app::gui {
namespace {

constexpr int kMaxScriptSeconds = 3600;

std::optional<double> number(const std::string& text) {
  if (text.empty()) return std::nullopt;
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  if (end != text.c_str() + text.size() || !std::isfinite(value)) return std::nullopt;
  return value;
}

std::string short_number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", value);
  return text;
}

}  // namespace

std::vector<ScriptAction> parse_script(const std::string& text, std::vector<ScriptError>& errors) {
  std::vector<ScriptAction> actions;
  std::istringstream in(text);
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
    std::size_t i = 0;
    if (const auto time = number(w[0])) {
      // A script is a demo or a test: an hour is plenty, and a time like 1e308 would
      // keep the window open for ever.
      if (!(*time >= 0 && *time <= kMaxScriptSeconds)) {
        errors.push_back({line, "the time must be from 0 to " + std::to_string(kMaxScriptSeconds) +
                                    " seconds, not '" + w[0] + "'"});
        continue;
      }
      action.at = *time;
      ++i;
    }
    if (i >= w.size()) {
      errors.push_back({line, "a time without an action"});
      continue;
    }
    const std::string verb = w[i];
    const std::string argument = i + 1 < w.size() ? w[i + 1] : "";
    if (i + 2 < w.size()) {
      errors.push_back({line, "too many words after '" + verb + "'"});
      continue;
    }
    Request& r = action.request;
    const auto need_number = [&](RequestKind kind, double low, double high) {
      const auto value = number(argument);
      if (!value || *value < low || *value > high) {
        errors.push_back({line, "'" + verb + "' needs a number from " + short_number(low) + " to " +
                                    short_number(high) +
                                    (argument.empty() ? "" : ", not '" + argument + "'")});
        return false;
      }
      r.kind = kind;
      r.value = *value;
      return true;
    };
    const auto no_argument = [&](RequestKind kind) {
      if (!argument.empty()) {
        errors.push_back({line, "'" + verb + "' takes no argument"});
        return false;
      }
      r.kind = kind;
      return true;
    };
    bool ok = false;
    if (verb == "load") {
      ok = need_number(RequestKind::SetLoad, 0.0, 1e300);
    } else if (verb == "method" || verb == "preconditioner") {
      const bool method = verb == "method";
      const bool known = method ? solver::parse_method(argument).has_value()
                                : solver::parse_preconditioner(argument).has_value();
      ok = !argument.empty() && known;
      if (argument.empty())
        errors.push_back({line, "'" + verb + "' needs a name"});
      else if (!known)
        errors.push_back({line, "unknown " + verb + " '" + argument + "' (" +
                                    (method ? "feti-c, mprgp, feti-dp, active-set, feti, cg or sd"
                                            : "dirichlet, lumped or none") +
                                    ")"});
      r.kind = method ? RequestKind::SetMethod : RequestKind::SetPreconditioner;
      r.text = argument;
    } else if (verb == "compare") {
      ok = argument == "none" || solver::parse_method(argument).has_value();
      if (!ok)
        errors.push_back({line, "'compare' needs a method or 'none', got '" + argument + "'"});
      r.kind = RequestKind::SetCompare;
      r.text = argument;
    } else if (verb == "magnification") {
      if (argument == "auto") {
        r.kind = RequestKind::SetMagnification;
        r.value = 0.0;
        ok = true;
      } else {
        ok = need_number(RequestKind::SetMagnification, 1e-300, 1e300);
      }
    } else if (verb == "play") {
      ok = no_argument(RequestKind::Play);
    } else if (verb == "pause") {
      ok = no_argument(RequestKind::Pause);
    } else if (verb == "step") {
      ok = no_argument(RequestKind::Step);
    } else if (verb == "back") {
      ok = no_argument(RequestKind::StepBack);
    } else if (verb == "reset") {
      ok = no_argument(RequestKind::Reset);
    } else if (verb == "cancel") {
      ok = no_argument(RequestKind::Cancel);
    } else if (verb == "live") {
      ok = argument == "on" || argument == "off";
      if (!ok) errors.push_back({line, "'live' needs on or off"});
      r.kind = RequestKind::SetLive;
      r.value = argument == "on" ? 1.0 : 0.0;
    } else if (verb == "scrub") {
      ok = need_number(RequestKind::Scrub, 0.0, 1e9);
    } else if (verb == "toggle") {
      ok = argument == "subdomains" || argument == "forces" || argument == "gaps" ||
           argument == "stress" || argument == "moment" || argument == "overlay" ||
           argument == "labels" || argument == "help";
      if (!ok)
        errors.push_back({line,
                          "'toggle' needs subdomains, forces, gaps, stress, moment, overlay, "
                          "labels or help"});
      r.kind = RequestKind::Toggle;
      r.text = argument;
    } else if (verb == "color") {
      ok = argument == "subdomain" || argument == "strut" || argument == "stress" ||
           argument == "moment";
      if (!ok) errors.push_back({line, "'color' needs subdomain, strut, stress or moment"});
      r.kind = RequestKind::SetColor;
      r.text = argument;
    } else if (verb == "screenshot") {
      r.kind = RequestKind::Screenshot;
      r.text = argument;
      ok = true;
    } else if (verb == "view") {
      ok = !argument.empty();
      if (!ok) errors.push_back({line, "'view' needs a view file"});
      r.kind = RequestKind::LoadView;
      r.text = argument;
    } else if (verb == "locate") {
      // "locate pair:K" or "locate node:STRUT:N" (indices): reported in the state file.
      std::string spaced = argument;
      std::replace(spaced.begin(), spaced.end(), ':', ' ');
      std::istringstream parts(spaced);
      std::string kind;
      long a = -1, b = -1;
      parts >> kind >> a;
      if (kind == "node") parts >> b;
      std::string rest;
      ok = ((kind == "pair" && a >= 0) || (kind == "node" && a >= 0 && b >= 0)) && !(parts >> rest);
      if (!ok) errors.push_back({line, "'locate' needs pair:K or node:STRUT:N"});
      r.kind = RequestKind::Locate;
      r.text = argument;
    } else if (verb == "screenshot-window") {
      r.kind = RequestKind::ScreenshotWindow;
      r.text = argument;
      ok = true;
    } else if (verb == "save-view") {
      r.kind = RequestKind::SaveView;
      r.text = argument;
      ok = true;
    } else if (verb == "record-iterations") {
      ok = no_argument(RequestKind::RecordIterations);
    } else if (verb == "record-sweep") {
      ok = need_number(RequestKind::RecordSweep, 2.0, 10000.0);
    } else if (verb == "export-vtu") {
      r.kind = RequestKind::ExportParaView;
      r.text = argument;
      ok = true;
    } else if (verb == "reload") {
      ok = no_argument(RequestKind::Reload);
    } else if (verb == "wait") {
      action.wait = no_argument(RequestKind::Quit);
      ok = action.wait;
    } else if (verb == "quit") {
      ok = no_argument(RequestKind::Quit);
    } else {
      errors.push_back({line, "unknown action '" + verb + "'"});
    }
    if (ok) actions.push_back(action);
  }
  return actions;
}

}  // namespace fetic::app::gui
