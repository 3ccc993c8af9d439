#pragma once
// Each fetic command registers itself on the command line; its callback stores the
// command's exit status in `exit_code`.

#include <CLI/CLI.hpp>

namespace fetic::app {

void register_solve(CLI::App& app, int& exit_code);
void register_bench(CLI::App& app, int& exit_code);
void register_generate(CLI::App& app, int& exit_code);
void register_render(CLI::App& app, int& exit_code);
void register_figures(CLI::App& app, int& exit_code);
void register_bench_render(CLI::App& app, int& exit_code);
void register_gui(CLI::App& app, int& exit_code);
void register_scenes(CLI::App& app, int& exit_code);

}  // namespace fetic::app
