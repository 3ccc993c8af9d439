#pragma once
// Each fetic command registers itself on the command line; its callback stores the
// command's exit status in `exit_code`.

#include <memory>
#include <string>
#include <utility>

#include <CLI/CLI.hpp>

namespace fetic::app {

// Adds the command `name` with a fresh Args for its options to fill; once they are parsed,
// its callback sets `exit_code` to `run(args)`. Returns the command, to add the options
// to, and the args.
template <typename Args>
std::pair<CLI::App*, std::shared_ptr<Args>> add_command(CLI::App& app, const std::string& name,
                                                        const std::string& description,
                                                        int& exit_code, int (*run)(const Args&)) {
  auto args = std::make_shared<Args>();
  CLI::App* command = app.add_subcommand(name, description);
  command->callback([args, run, &exit_code] { exit_code = run(*args); });
  return {command, args};
}

void register_solve(CLI::App& app, int& exit_code);
void register_bench(CLI::App& app, int& exit_code);
void register_generate(CLI::App& app, int& exit_code);
void register_render(CLI::App& app, int& exit_code);
void register_figures(CLI::App& app, int& exit_code);
void register_bench_render(CLI::App& app, int& exit_code);
void register_gui(CLI::App& app, int& exit_code);
void register_scenes(CLI::App& app, int& exit_code);

}  // namespace fetic::app
