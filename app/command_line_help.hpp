#pragma once
// The command line's own help: `fetic help [COMMAND]`, and "did you mean" for an option
// the command does not have.

#include <string>

#include <CLI/CLI.hpp>

namespace fetic::app {

// Registers `fetic help [COMMAND]`: the program's or the command's --help text.
void register_help(CLI::App& app, int& exit_code);

// For an argument list CLI11 refused with "not expected": one line per unknown option of
// the command given as argv[1] ("unknown option '--methd'; did you mean '--method'?"), or
// "" when none of the arguments is an unknown option (CLI11's message then stands).
std::string unknown_option_message(const CLI::App& app, int argc, char** argv);

// The option name of `names` nearest to `word` (edit distance), or "" when none is close.
std::string nearest_name(const std::string& word, const std::vector<std::string>& names);

}  // namespace fetic::app
