#include "app/view_file.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "app/output_file.hpp"
#include "scenes/scene_error.hpp"

namespace fetic::app {
namespace {

using nlohmann::json;

// Reads one entry, checking its type and range; the message names the entry.
class Reader {
 public:
  explicit Reader(const std::string& path) : path_(path) {}

  [[noreturn]] void fail(const std::string& key, const std::string& problem) const {
    throw ViewFileError(scenes::printable(path_) + ": '" + key + "' " + problem);
  }
  const json* find(const json& in, const std::string& key) const {
    const auto it = in.find(key);
    return it == in.end() ? nullptr : &*it;
  }
  std::optional<double> number(const json& in, const std::string& key, double low,
                               bool positive = false) const {
    const json* value = find(in, key);
    if (!value) return std::nullopt;
    if (!value->is_number()) fail(key, "must be a number");
    const double x = value->get<double>();
    if (!std::isfinite(x) || x < low || (positive && x <= 0.0))
      fail(key, positive ? "must be a positive number" : "must be at least " + std::to_string(low));
    return x;
  }
  std::optional<bool> boolean(const json& in, const std::string& key) const {
    const json* value = find(in, key);
    if (!value) return std::nullopt;
    if (!value->is_boolean()) fail(key, "must be true or false");
    return value->get<bool>();
  }
  void only(const json& in, std::initializer_list<const char*> keys,
            const std::string& where) const {
    for (const auto& [key, value] : in.items()) {
      bool known = false;
      for (const char* k : keys)
        known = known || key == k;
      if (!known) {
        std::string list;
        for (const char* k : keys)
          list += (list.empty() ? "" : ", ") + std::string(k);
        throw ViewFileError(scenes::printable(path_) + ": unknown entry '" +
                            scenes::printable(key) + "'" + where + " (known: " + list + ")");
      }
    }
  }

 private:
  const std::string& path_;
};

}  // namespace

const char* color_name(render::ColorBy color) {
  switch (color) {
    case render::ColorBy::Stress:
      return "stress";
    case render::ColorBy::Strut:
      return "strut";
    case render::ColorBy::Moment:
      return "moment";
    case render::ColorBy::Subdomain:
      break;
  }
  return "subdomain";
}

std::optional<render::ColorBy> color_from_name(const std::string& name) {
  for (const render::ColorBy color : {render::ColorBy::Subdomain, render::ColorBy::Stress,
                                      render::ColorBy::Strut, render::ColorBy::Moment})
    if (name == color_name(color)) return color;
  return std::nullopt;
}

SavedView read_view_file(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw ViewFileError(scenes::printable(path) + ": cannot read the view file");
  std::stringstream text;
  text << in.rdbuf();
  json root;
  try {
    root = json::parse(text.str());
  } catch (const json::parse_error& error) {
    // nlohmann gives the byte; say the line.
    const std::string content = text.str();
    const std::size_t byte = std::min<std::size_t>(error.byte, content.size());
    const long line =
        1 + std::count(content.begin(),
                       content.begin() + static_cast<long>(byte > 0 ? byte - 1 : 0), '\n');
    throw ViewFileError(scenes::printable(path) + ":" + std::to_string(line) +
                        ": not a JSON view file (" + error.what() + ")");
  }
  if (!root.is_object())
    throw ViewFileError(scenes::printable(path) + ": a view file is a JSON object");
  const Reader r(path);
  r.only(root, {"fetic_view", "size", "center", "zoom", "magnification", "color", "show", "scales"},
         "");
  SavedView view;
  if (const json* size = r.find(root, "size")) {
    if (!size->is_array() || size->size() != 2 || !(*size)[0].is_number_integer() ||
        !(*size)[1].is_number_integer() || (*size)[0].get<long>() < 16 ||
        (*size)[1].get<long>() < 16 || (*size)[0].get<long>() > 16384 ||
        (*size)[1].get<long>() > 16384)
      r.fail("size", "must be [width, height] in pixels, each 16 to 16384");
    view.width = (*size)[0].get<int>();
    view.height = (*size)[1].get<int>();
  }
  if (const json* center = r.find(root, "center")) {
    if (!center->is_array() || center->size() != 2 || !(*center)[0].is_number() ||
        !(*center)[1].is_number() || !std::isfinite((*center)[0].get<double>()) ||
        !std::isfinite((*center)[1].get<double>()))
      r.fail("center", "must be [x, y] in the scene's length unit");
    view.center_x = (*center)[0].get<double>();
    view.center_y = (*center)[1].get<double>();
  }
  view.zoom = r.number(root, "zoom", 0.0, true);
  if (view.zoom && (*view.zoom < 0.01 || *view.zoom > 1000.0))
    r.fail("zoom", "must be between 0.01 and 1000");
  view.magnification = r.number(root, "magnification", 0.0);
  if (const json* color = r.find(root, "color")) {
    view.color_by = color_from_name(color->is_string() ? color->get<std::string>() : "");
    if (!view.color_by)
      r.fail("color", "must be \"subdomain\", \"stress\", \"strut\" or \"moment\"");
  }
  if (const json* show = r.find(root, "show")) {
    if (!show->is_object()) r.fail("show", "must be an object of true/false toggles");
    r.only(*show, {"forces", "gaps", "overlay", "labels"}, " in 'show'");
    view.forces = r.boolean(*show, "forces");
    view.gaps = r.boolean(*show, "gaps");
    view.overlay = r.boolean(*show, "overlay");
    view.labels = r.boolean(*show, "labels");
  }
  if (const json* scales = r.find(root, "scales")) {
    if (!scales->is_object()) r.fail("scales", "must be an object");
    r.only(*scales,
           {"displacement", "force", "stress", "moment", "iterations", "active_set", "residual_low",
            "residual_high", "stretch", "lateral"},
           " in 'scales'");
    render::RunExtent extent;
    extent.largest_displacement = r.number(*scales, "displacement", 0.0).value_or(0.0);
    extent.largest_force = r.number(*scales, "force", 0.0).value_or(0.0);
    extent.largest_stress = r.number(*scales, "stress", 0.0).value_or(0.0);
    extent.largest_moment = r.number(*scales, "moment", 0.0).value_or(0.0);
    extent.largest_iteration = static_cast<int>(r.number(*scales, "iterations", 0.0).value_or(0.0));
    extent.largest_active_set =
        static_cast<int>(r.number(*scales, "active_set", 0.0).value_or(0.0));
    extent.smallest_residual = r.number(*scales, "residual_low", 0.0).value_or(0.0);
    extent.largest_residual = r.number(*scales, "residual_high", 0.0).value_or(0.0);
    extent.largest_stretch = r.number(*scales, "stretch", 0.0).value_or(0.0);
    if (const json* lateral = r.find(*scales, "lateral")) {
      if (!lateral->is_array()) r.fail("lateral", "must be a list of numbers, one per strut");
      for (const json& x : *lateral) {
        if (!x.is_number() || !std::isfinite(x.get<double>()) || x.get<double>() < 0.0)
          r.fail("lateral", "must be a list of numbers, one per strut");
        extent.strut_lateral.push_back(x.get<double>());
      }
    }
    view.scales = extent;
  }
  return view;
}

std::string view_json(const SavedView& view) {
  nlohmann::ordered_json root;
  root["fetic_view"] = 1;
  if (view.width && view.height) root["size"] = {*view.width, *view.height};
  if (view.center_x && view.center_y) root["center"] = {*view.center_x, *view.center_y};
  if (view.zoom) root["zoom"] = *view.zoom;
  if (view.magnification) root["magnification"] = *view.magnification;
  if (view.color_by) root["color"] = color_name(*view.color_by);
  nlohmann::ordered_json show = nlohmann::ordered_json::object();
  if (view.forces) show["forces"] = *view.forces;
  if (view.gaps) show["gaps"] = *view.gaps;
  if (view.overlay) show["overlay"] = *view.overlay;
  if (view.labels) show["labels"] = *view.labels;
  if (!show.empty()) root["show"] = show;
  if (view.scales) {
    const render::RunExtent& e = *view.scales;
    root["scales"] = {{"displacement", e.largest_displacement},
                      {"force", e.largest_force},
                      {"stress", e.largest_stress},
                      {"moment", e.largest_moment},
                      {"iterations", e.largest_iteration},
                      {"active_set", e.largest_active_set},
                      {"residual_low", e.smallest_residual},
                      {"residual_high", e.largest_residual},
                      {"stretch", e.largest_stretch},
                      {"lateral", e.strut_lateral}};
  }
  return root.dump(1) + '\n';
}

void write_view_file(const std::string& path, const SavedView& view) {
  write_output(path, view_json(view));
}

void apply_view(const SavedView& saved, render::View& view) {
  if (saved.width) view.width = *saved.width;
  if (saved.height) view.height = *saved.height;
  if (saved.magnification) view.magnification = *saved.magnification;
  if (saved.color_by) view.color_by = *saved.color_by;
  if (saved.forces) view.show_forces = *saved.forces;
  if (saved.gaps) view.show_gaps = *saved.gaps;
  if (saved.overlay) view.show_overlay = *saved.overlay;
  if (saved.labels) view.show_labels = *saved.labels;
  if (saved.zoom) view.zoom = *saved.zoom;
  if (saved.center_x && saved.center_y) {
    view.centered = true;
    view.center_x = *saved.center_x;
    view.center_y = *saved.center_y;
  }
}

void apply_scales(const std::optional<render::RunExtent>& scales, render::RunExtent& extent) {
  if (!scales) return;
  const render::RunExtent& s = *scales;
  extent.largest_displacement = s.largest_displacement;
  extent.largest_force = s.largest_force;
  extent.largest_stress = s.largest_stress;
  extent.largest_moment = s.largest_moment;
  extent.largest_iteration = s.largest_iteration;
  extent.largest_active_set = s.largest_active_set;
  extent.smallest_residual = s.smallest_residual;
  extent.largest_residual = s.largest_residual;
  extent.largest_stretch = s.largest_stretch;
  extent.strut_lateral = s.strut_lateral;
}

}  // namespace fetic::app
