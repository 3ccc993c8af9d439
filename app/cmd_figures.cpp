// fetic figures --out DIR: the thesis' figures (docs/METHODS.md 5) drawn from the
// running code, one PNG each. Figures whose method is not available are skipped with the
// reason; the others are still written.

#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "app/commands.hpp"
#include "app/data_paths.hpp"
#include "app/exit_codes.hpp"
#include "app/interrupt.hpp"
#include "app/out_of_memory.hpp"
#include "app/output_file.hpp"
#include "app/output_options.hpp"
#include "app/render_output.hpp"
#include "app/scene_input.hpp"
#include "render/figures.hpp"
#include "scenes/scene_error.hpp"

namespace fetic::app {
namespace {

struct FiguresArgs {
  std::string out;
  std::string size = "1200x800";
  std::vector<std::string> figures;  // empty: all
  std::string scene = bundled_scene("thesis.toml");
};

int run_figures(const FiguresArgs& args) {
  std::vector<std::string> ids = args.figures;
  if (ids.empty())
    for (const render::FigureInfo& info : render::figure_catalogue())
      ids.push_back(info.id);
  bool needs_thesis = false;
  for (const std::string& id : ids)
    needs_thesis = needs_thesis || id.starts_with("9.");

  if (!make_output_directory(args.out)) return kExitOutput;
  auto headless = open_headless(args.out);
  if (!headless) return kExitNoDisplay;

  std::optional<scenes::Scene> scene;
  std::optional<solver::Model> thesis;
  std::string thesis_problem;
  int scene_status = kExitOk;
  if (needs_thesis) {
    scene = load_scene_or_report(args.scene, scene_status);
    if (scene_status == kExitInterrupted) return scene_status;
    if (scene && !memory_suffices(
                     *scene, args.scene,
                     {{solver::MethodKind::ActiveSet, solver::MethodKind::FetiC,
                       solver::MethodKind::Mprgp, solver::MethodKind::Feti,
                       solver::MethodKind::ConjugateGradient, solver::MethodKind::SteepestDescent},
                      false,
                      0},
                     scene_status))
      return scene_status;
    if (scene) {
      thesis = solver::build_model(*scene);
    } else {
      thesis_problem = args.scene + ": the thesis scene could not be loaded (--scene)";
    }
  }

  const ImageSize size = *parse_image_size(args.size);
  render::FigureMaker maker(thesis ? &*thesis : nullptr, thesis_problem);
  int written = 0, skipped = 0;
  for (const std::string& id : ids) {
    if (interrupted()) {
      std::cerr << scenes::printable(args.out) << ": interrupted by " << interrupt_name()
                << " after " << written << " complete figure(s)\n";
      return kExitInterrupted;
    }
    const render::Figure figure = maker.make(id, size.width, size.height);
    if (!figure.drawing) {
      std::cerr << "skipped      figure " << id
                << (figure.info.file.empty() ? "" : " (" + figure.info.file + ")") << ": "
                << figure.note << '\n';
      ++skipped;
      continue;
    }
    const std::string path = (std::filesystem::path(args.out) / figure.info.file).string();
    try {
      const render::Image image = headless->renderer->render(
          size.width, size.height, {&*figure.drawing}, render::Color{255, 255, 255, 255});
      write_png_atomically(path, render::encode_png(image));
    } catch (const OutputError& error) {
      return report_output_error(error);
    } catch (const render::RenderError& error) {
      std::cerr << scenes::printable(path) << ": rendering failed: " << error.what() << '\n';
      return kExitOutput;
    }
    std::cout << "figure " << id << "   " << path << "  " << figure.info.what
              << (figure.note.empty() ? "" : " - " + figure.note) << '\n';
    ++written;
  }
  std::cout << written << " figure(s) written to " << args.out;
  if (skipped > 0) std::cout << ", " << skipped << " skipped (reasons above)";
  std::cout << '\n';
  if (scene_status != kExitOk) return scene_status;
  return written > 0 ? kExitOk : kExitSolverSetup;
}

}  // namespace

void register_figures(CLI::App& app, int& exit_code) {
  const auto [command, args] =
      add_command(app, "figures",
                  "Draw the thesis' figures (2.1, 3.2, 4.3, 9.2, 9.3, 9.4) and S.1 (iterations "
                  "against subdomains: active set, FETI-C, MPRGP) as PNG",
                  exit_code, run_figures);
  command->add_option("--out", args->out, "Directory for the PNG files")
      ->required()
      ->check(output_name(OutputKind::Folder));
  add_image_size_option(command, args->size);
  std::vector<std::string> ids;
  for (const render::FigureInfo& info : render::figure_catalogue())
    ids.push_back(info.id);
  command->add_option("--figure", args->figures, "Only these figures (repeatable; default all)")
      ->check(CLI::IsMember(ids));
  look_up_bundled_scenes(
      command->add_option("--scene", args->scene, "The thesis scene, for figures 9.x"))
      ->capture_default_str();
}

}  // namespace fetic::app
