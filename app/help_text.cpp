#include "app/help_text.hpp"

#include <map>

namespace fetic::app {
namespace {

// Exit statuses (app/exit_codes.hpp), one line each, picked per command.
const std::map<int, const char*> kStatus = {
    {0, "  0    success"},
    {1, "  1    bad command line"},
    {2, "  2    the scene file is missing or invalid (each problem as file:line: message)"},
    {3, "  3    the method cannot solve this scene (contacts for sd/cg, a singular strut)"},
    {4,
     "  4    no convergence within the cap, or an unbounded scene (outputs still written,\n"
     "       \"converged\": false)"},
    {5, "  5    an output file or directory could not be written"},
    {6, "  6    no display: no EGL device to render with (gui: no X display)"},
    {7,
     "  7    not enough memory: the scene needs more than is available (refused before the\n"
     "       work, with the estimate; FETIC_MEMORY_CHECK=off tries anyway)"},
    {130, "  130  interrupted by SIGINT or SIGTERM (Ctrl-C)"},
};

std::string statuses(std::initializer_list<int> codes) {
  std::string text = "Exit status:\n";
  for (int code : codes)
    text += std::string(kStatus.at(code)) + "\n";
  return text;
}

const char* kSceneUnits =
    "Units: the scene's own, consistently (SI in the bundled scenes): lengths and\n"
    "displacements [m], forces and reactions [N], loads per length [N/m], E and stresses\n"
    "[Pa], areas [m^2]; the load factor, tolerances and residuals have no unit.\n";

// A command's footer: its examples, its exit statuses, notes, the scene's units (where it
// reads a scene's numbers) and a last note.
struct Footer {
  const char* command;
  const char* examples;
  std::initializer_list<int> codes;
  const char* notes;
  bool units;
  const char* last;
};

const Footer kFooters[] = {
    {"solve",
     "Examples:\n"
     "  fetic solve scenes/two_bars.toml --json result.json\n"
     "  fetic solve scenes/two_bars.toml --load-steps 0:2:21 --csv-steps curve.csv \\\n"
     "              --vtu paraview/          # then: paraview paraview/struts.pvd\n\n",
     {0, 1, 2, 3, 4, 5, 7, 130},
     "  After SIGINT/SIGTERM the --json, --csv, --csv-steps and --vtu outputs are still\n"
     "  written, with the current iterate marked \"interrupted\": true.\n\n",
     true,
     "Progress: a line on stderr when it is a terminal (--progress forces, --quiet "
     "silences).\n"},
    {"render",
     "Examples:\n"
     "  fetic render scenes/thesis.toml --out frames/ --movie thesis.mp4\n"
     "  fetic render scenes/two_bars.toml --out frames/ --load-steps 0:2:21 --vtu vtu/\n\n",
     {0, 1, 2, 3, 4, 5, 6, 7, 130},
     "\n",
     true,
     "Image sizes are in pixels; --magnification scales displacements and gaps in the "
     "picture.\n"},
    {"figures",
     "Example:\n"
     "  fetic figures --out figures/     # works from any directory\n\n",
     {0, 1, 2, 3, 5, 6, 7, 130},
     "  Status 3: no figure could be drawn; figures that cannot be drawn are skipped\n"
     "  with the reason.\n\nImage sizes are in pixels.\n",
     false,
     ""},
    {"bench",
     "Example:\n"
     "  fetic bench --repeat 5 --csv bench.csv    # the bundled scenes\n\n",
     {0, 1, 2, 3, 5, 7, 130},
     "\nTimes are in milliseconds; ratios are to the active-set method measured in the\n"
     "same run.\n",
     false,
     ""},
    {"bench-render",
     "Example:\n"
     "  fetic bench-render --frames 60 --size 1280x720\n\n",
     {0, 1, 2, 3, 5, 6, 7, 130},
     "\nReports frames per second; image sizes are in pixels.\n",
     false,
     ""},
    {"gui",
     "Example:\n"
     "  fetic gui scenes/thesis.toml --max-load 2\n\n",
     {0, 1, 2, 3, 4, 5, 6, 7, 130},
     "\n",
     true,
     ""},
    {"generate",
     "Example:\n"
     "  fetic generate --model plane --pairs 20 --elements 40,8 --subdomains 4,2 -o "
     "big.toml\n\n",
     {0, 1, 5, 7, 130},
     "\nThe scene is in SI units: lengths [m], E [Pa], forces [N].\n",
     false,
     ""},
    {"scenes",
     "Example:\n  fetic scenes             # then: fetic solve thesis --json r.json\n\n",
     {0, 1, 2, 5},
     "  Status 2: no bundled scene folder was found.\n",
     false,
     ""},
    {"help", "Example:\n  fetic help solve\n\n", {0, 1, 5}, "", false, ""},
};

}  // namespace

std::string help_footer(const std::string& command) {
  for (const Footer& footer : kFooters)
    if (command == footer.command)
      return footer.examples + statuses(footer.codes) + footer.notes +
             (footer.units ? kSceneUnits : "") + footer.last;
  return {};
}

void add_help_footers(CLI::App& app) {
  app.footer(
      "Run `fetic help COMMAND` (or `fetic COMMAND --help`) for a command's options, an example, "
      "its exit statuses "
      "and units.\nDocumentation: README.md and docs/ (installed in share/doc/fetic).");
  for (CLI::App* command : app.get_subcommands([](CLI::App*) { return true; })) {
    const std::string footer = help_footer(command->get_name());
    if (!footer.empty()) command->footer(footer);
  }
}

}  // namespace fetic::app
