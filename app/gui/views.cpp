// How the window's picture is drawn: the requests that change it (magnification,
// colouring, toggles, pan and zoom; App::apply passes them here), and saved views
// (docs/WINDOW.md, "Views"): the picture's size, the world point at the centre of the
// scene region and the zoom, the magnification as shown, the colouring, toggles and the
// scales the picture is drawn with, written as the JSON of app/view_file.hpp and read
// back. `fetic render --view` draws the same picture headless.

#include <iostream>
#include <string>

#include <imgui.h>

#include "app/exit_codes.hpp"
#include "app/gui/app.hpp"
#include "app/interrupt.hpp"
#include "app/output_file.hpp"
#include "render/scene_framing.hpp"

namespace fetic::app::gui {

// How the picture is drawn: magnification, colouring, toggles, pan and zoom, views.
void App::apply_display_request(const Request& r) {
  switch (r.kind) {
    case RequestKind::SetMagnification:
      magnification_ = r.value;
      redraw_ = true;
      break;
    case RequestKind::Toggle:
      if (r.text == "subdomains") subdomains_ = !subdomains_;
      if (r.text == "forces") forces_ = !forces_;
      if (r.text == "gaps") gaps_ = !gaps_;
      // Stress and moment exclude each other; off, the subdomain or strut colours return.
      if (r.text == "stress") {
        stress_ = !stress_;
        if (stress_) moment_ = false;
      }
      if (r.text == "moment") {
        moment_ = !moment_;
        if (moment_) stress_ = false;
      }
      if (r.text == "overlay") show_overlay_ = !show_overlay_;
      if (r.text == "labels") labels_ = !labels_;
      if (r.text == "corners") corners_ = !corners_;
      if (r.text == "chart") {
        chart_ = !chart_;
        framing_key_ = {};  // the scene region changes
      }
      if (r.text == "help") help_ = !help_;
      redraw_ = true;
      break;
    case RequestKind::SetColor:
      if (const auto color = color_from_name(r.text)) set_color(*color);
      redraw_ = true;
      break;
    case RequestKind::ResetView:
      zoom_ = 1.0f;
      pan_ = {0.0f, 0.0f};
      redraw_ = true;
      break;
    case RequestKind::LoadView:
      load_view(r);
      break;
    default:
      break;
  }
}

SavedView App::current_view() const {
  SavedView saved;
  saved.width = view_width_;
  saved.height = view_height_;
  if (placed_.pixels_per_unit > 0.0) {
    // The world point drawn at the centre of the scene region.
    const render::Point middle{0.5f * (placed_.region.x0 + placed_.region.x1),
                               0.5f * (placed_.region.y0 + placed_.region.y1)};
    saved.center_x =
        placed_.world_center.x() +
        (static_cast<double>(middle.x) - placed_.pixel_center.x) / placed_.pixels_per_unit;
    saved.center_y =
        placed_.world_center.y() -
        (static_cast<double>(middle.y) - placed_.pixel_center.y) / placed_.pixels_per_unit;
  }
  saved.zoom = zoom_;
  // The window's text is at least this big: `fetic render --view` draws it the same.
  saved.text_size = view(view_width_, view_height_).min_text_size;
  // 0: automatic, chosen again from the scales (as the window does, with its caption note).
  saved.magnification = magnification_;
  const render::View v = view(view_width_, view_height_);
  saved.color_by = v.color_by;
  saved.scale_basis = v.scale_basis;
  saved.forces = forces_;
  saved.gaps = gaps_;
  saved.overlay = show_overlay_;
  saved.labels = labels_;
  saved.corners = corners_;
  if (shown_ && shown_->extent) saved.scales = drawn_extent_;
  return saved;
}

// Stress and moment leave the subdomain-or-strut choice beneath them as it is.
void App::set_color(render::ColorBy color) {
  stress_ = color == render::ColorBy::Stress;
  moment_ = color == render::ColorBy::Moment;
  if (color == render::ColorBy::Subdomain) subdomains_ = true;
  if (color == render::ColorBy::Strut) subdomains_ = false;
}

void App::view_buttons() {
  if (ImGui::Button("Save view (V)")) push({RequestKind::SaveView, 0.0, {}});
  ImGui::SameLine();
  ImGui::BeginDisabled(view_path_.empty());
  if (ImGui::Button("Load view")) push({RequestKind::LoadView, 0.0, view_path_});
  ImGui::EndDisabled();
  if (!view_path_.empty() && ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
    ImGui::SetTooltip("%s", view_path_.c_str());
}

void App::save_view(const std::string& path) {
  // Numbered: fetic_view_0000.json first; the number is used up only by a saved view.
  const auto [file, number] = path.empty() ? numbered_name("fetic_view_%04d.json", views_saved_)
                                           : std::make_pair(in_screenshot_dir(path), -1);
  if (!output_folder_ready(file)) return;
  try {
    write_view_file(file, current_view());
    if (number >= 0) views_saved_ = number + 1;
    view_path_ = file;
    log_.write({{"event", "view saved"}, {"path", file}});
    say("view saved as " + file);
  } catch (const OutputError& error) {
    say(error.what(), true);
    log_.output_lost(error.what());
  }
}

void App::load_view(const Request& request) {
  const std::string& path = request.text;
  try {
    use_view(read_view_file(path));
    view_path_ = path;
    log_.write({{"event", "view loaded"}, {"path", path}});
    say("view " + path);
  } catch (const ViewFileError& error) {
    fail(request, error.what(), interrupted() ? kExitInterrupted : kExitUsage);
  }
}

void App::use_view(const SavedView& saved) {
  if (saved.magnification) magnification_ = *saved.magnification;
  if (saved.color_by) set_color(*saved.color_by);
  if (saved.forces) forces_ = *saved.forces;
  if (saved.gaps) gaps_ = *saved.gaps;
  if (saved.overlay) show_overlay_ = *saved.overlay;
  if (saved.labels) labels_ = *saved.labels;
  if (saved.corners) corners_ = *saved.corners;
  if (saved.zoom) zoom_ = static_cast<float>(*saved.zoom);
  if (saved.center_x && saved.center_y) {
    // Placed when the picture is next framed (the fit depends on the frame's size).
    center_pending_ = true;
    pending_center_ = {*saved.center_x, *saved.center_y};
  }
  scales_ = saved.scales;
  framing_key_ = {};  // fitted again, with the view's scales
  redraw_ = true;
}

void App::place_pending_center() {
  if (!center_pending_) return;
  center_pending_ = false;
  render::View v;
  v.zoom = zoom_;
  v.centered = true;
  v.center_x = pending_center_.x();
  v.center_y = pending_center_.y();
  const render::Point center = render::placed(framing_, v).pixel_center;
  pan_ = {center.x - base_center_.x, center.y - base_center_.y};
}

std::string App::in_screenshot_dir(const std::string& path) const {
  const std::filesystem::path p(path);
  return p.is_absolute() ? path : (std::filesystem::path(args_.screenshot_dir) / p).string();
}

}  // namespace fetic::app::gui
