#pragma once
// What `fetic COMMAND --help` prints after the options: an example, the exit statuses the
// command can return, and the units of what it reads and writes (docs/COMMANDS.md).

#include <string>

#include <CLI/CLI.hpp>

namespace fetic::app {

// The footer of one command ("solve", "render", ...); empty for an unknown name.
std::string help_footer(const std::string& command);

// Sets the footer of the program and of every registered command.
void add_help_footers(CLI::App& app);

}  // namespace fetic::app
