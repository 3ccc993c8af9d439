#include "app/command_line_help.hpp"

#include <algorithm>
#include <iostream>
#include <memory>
#include <vector>

#include "app/exit_codes.hpp"
#include "scenes/message_text.hpp"
#include "scenes/scene_error.hpp"

namespace fetic::app {
namespace {

// Every "--name" the command accepts (its own and the program's).
std::vector<std::string> long_names(const CLI::App& command) {
  std::vector<std::string> names;
  for (const CLI::App* app = &command; app; app = app->get_parent())
    for (const CLI::Option* option : app->get_options())
      for (const std::string& name : option->get_lnames())
        names.push_back("--" + name);
  return names;
}

int run_help(const CLI::App& app, const std::string& topic) {
  // (App::help() would show the help of the command being run - `help` itself.)
  if (topic.empty()) {
    std::cout << app.get_formatter()->make_help(&app, app.get_name(), CLI::AppFormatMode::Normal);
    return kExitOk;
  }
  for (const CLI::App* command : app.get_subcommands({}))
    if (command->check_name(topic)) {
      std::cout << command->help(app.get_name());  // as `fetic COMMAND --help` shows it
      return kExitOk;
    }
  std::string commands;
  for (const CLI::App* command : app.get_subcommands({}))
    commands += (commands.empty() ? "" : ", ") + command->get_name();
  std::cerr << "fetic help: no command '" << scenes::printable(topic) << "' (commands: " << commands
            << ")\n";
  return kExitUsage;
}

}  // namespace

std::string nearest_name(const std::string& word, const std::vector<std::string>& names) {
  std::string best;
  size_t best_distance = std::max<size_t>(2, word.size() / 3) + 1;
  for (const std::string& name : names) {
    // A prefix of one name only ("--meth") is as good as a typo.
    const bool prefix = name.size() > word.size() && name.compare(0, word.size(), word) == 0;
    const size_t distance =
        prefix ? 1 : scenes::edit_distance(word, name, scenes::LetterCase::Exact);
    if (distance < best_distance) {
      best = name;
      best_distance = distance;
    }
  }
  return best;
}

void register_help(CLI::App& app, int& exit_code) {
  CLI::App* command = app.add_subcommand("help", "Show the help of the program or of one command");
  auto topic = std::make_shared<std::string>();
  command->add_option("command", *topic, "The command (solve, render, ...)");
  command->callback([&app, &exit_code, topic] { exit_code = run_help(app, *topic); });
}

std::string unknown_option_message(const CLI::App& app, int argc, char** argv) {
  if (argc < 2) return "";
  const CLI::App* command = nullptr;
  for (const CLI::App* candidate : app.get_subcommands({}))
    if (candidate->check_name(argv[1])) command = candidate;
  if (!command) return "";
  const std::vector<std::string> names = long_names(*command);
  std::string message;
  for (int k = 2; k < argc; ++k) {
    const std::string argument = argv[k];
    if (argument == "--") break;
    if (argument.size() < 3 || argument.compare(0, 2, "--") != 0) continue;
    const std::string name = argument.substr(0, argument.find('='));
    if (std::find(names.begin(), names.end(), name) != names.end()) continue;
    message +=
        "fetic " + command->get_name() + ": unknown option '" + scenes::printable(name) + "'";
    const std::string suggestion = nearest_name(name, names);
    message += suggestion.empty() ? "" : "; did you mean '" + suggestion + "'?";
    message += "\n";
  }
  if (!message.empty()) message += "(fetic help " + command->get_name() + " lists its options)\n";
  return message;
}

}  // namespace fetic::app
