// The "ParaView export" button (and the script's export-vtu): the iterate on screen
// becomes the next frame of a ParaView series (struts.pvd, contacts.pvd) in --vtu-dir.

#include <exception>
#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "app/exit_codes.hpp"
#include "app/gui/app.hpp"

namespace fetic::app::gui {

void App::export_paraview(const Request& request) {
  if (!shown_ || shown_->iterates.empty()) {
    fail(request, "export-vtu: nothing to export yet: no solve is on screen", kExitUsage);
    return;
  }
  const std::string directory = request.text.empty() ? args_.vtu_dir : request.text;
  const int iteration = shown_index();
  const solver::Snapshot& state = *shown_->iterates[static_cast<std::size_t>(iteration)];
  try {
    // A new series for another directory or a reloaded scene.
    if (!vtu_ || vtu_->directory() != directory || vtu_model_ != shown_->model) {
      vtu_model_ = shown_->model;
      vtu_ = std::make_unique<VtuSeries>(directory, *vtu_model_, VtkEncoding::Zlib);
    }
    vtu_->write(state, vtu_->frames());
    const std::string file = (std::filesystem::path(directory) / "struts.pvd").string();
    status_line_ = "ParaView frame " + std::to_string(vtu_->frames()) + " in " + file;
    log_.write({{"event", "paraview"},
                {"directory", directory},
                {"frames", vtu_->frames()},
                {"load_factor", shown_->load_factor},
                {"iteration", iteration}});
  } catch (const std::exception& error) {
    vtu_.reset();
    fail(request, error.what(), kExitOutput);
  }
}

}  // namespace fetic::app::gui
