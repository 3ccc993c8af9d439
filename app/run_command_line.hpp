#pragma once
// The command line of fetic (app/run_command_line.cpp); apart from commands.hpp so that
// main.cpp does not include CLI11, whose header-only code costs seconds of compiling in
// every file that includes it.

namespace fetic::app {

// Parses the command line and runs the command; returns its exit status.
int run_command_line(int argc, char** argv);

}  // namespace fetic::app
