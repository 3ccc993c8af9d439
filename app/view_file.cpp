#include "app/view_file.hpp"

#include <algorithm>
#include <cmath>
#include <iostream>

#include <nlohmann/json.hpp>

#include "app/exit_codes.hpp"
#include "app/image_size.hpp"
#include "app/interrupt.hpp"
#include "app/json_input.hpp"
#include "app/output_file.hpp"
#include "scenes/enum_names.hpp"
#include "scenes/scene_error.hpp"

namespace fetic::app {
namespace {

using nlohmann::json;

// The numeric entries of a view file and their ranges (the same as the command line's
// where it has the option: --size 16..8192).
struct NumberRange {
  const char* entry;  // as parse_json_input names it: "zoom", "center[0]", "scales.force"
  double low, high;
  const char* text;
};
constexpr double kLargestScale = 1e300;  // scales: any finite non-negative value
const NumberRange kRanges[] = {
    {"size[0]", kMinImageSide, kMaxImageSide, "a whole number of pixels from 16 to 8192"},
    {"size[1]", kMinImageSide, kMaxImageSide, "a whole number of pixels from 16 to 8192"},
    {"center[0]", -1e15, 1e15, "from -1e15 to 1e15 (the scene's length unit)"},
    {"center[1]", -1e15, 1e15, "from -1e15 to 1e15 (the scene's length unit)"},
    {"zoom", 0.01, 1000.0, "from 0.01 to 1000"},
    {"magnification", 1e-12, 1e15, "\"auto\" or a number from 1e-12 to 1e15"},
    {"fetic_view", 1, 1, "1 (the format's version)"},
    {"text_size", 0, 200, "a number of pixels from 0 to 200"},
    {"scales.displacement", 0, kLargestScale, "a number from 0 to 1e300"},
    {"scales.force", 0, kLargestScale, "a number from 0 to 1e300"},
    {"scales.stress", 0, kLargestScale, "a number from 0 to 1e300"},
    {"scales.moment", 0, kLargestScale, "a number from 0 to 1e300"},
    {"scales.residual_low", 0, kLargestScale, "a number from 0 to 1e300"},
    {"scales.residual_high", 0, kLargestScale, "a number from 0 to 1e300"},
    {"scales.stretch", 0, kLargestScale, "a number from 0 to 1e300"},
    {"scales.iterations", 0, 1e9, "a whole number from 0 to 1e9"},
    {"scales.active_set", 0, 1e9, "a whole number from 0 to 1e9"},
    {"scales.lateral[]", 0, kLargestScale, "a list of numbers from 0 to 1e300, one per strut"},
};

// "scales.lateral[3]" -> "scales.lateral[]": one range for every element of a list.
const NumberRange* view_range_of(const std::string& entry) {
  const bool element = entry.rfind("scales.lateral[", 0) == 0;
  for (const NumberRange& range : kRanges)
    if (entry == range.entry || (element && std::string(range.entry) == "scales.lateral[]"))
      return &range;
  return nullptr;
}

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
  // A number within its range (kRanges[entry]); whole numbers only for `whole`.
  double checked(const json& value, const std::string& entry, bool whole = false) const {
    const NumberRange* range = view_range_of(entry);
    const std::string must = "must be " + std::string(range ? range->text : "a number");
    if (!value.is_number()) fail(entry, must + ", not " + quoted_value(value.dump()));
    const double x = value.get<double>();
    const bool integral = value.is_number_integer() || (whole && x == std::floor(x));
    if (!std::isfinite(x) || (whole && !integral) || (range && (x < range->low || x > range->high)))
      fail(entry, must + ", not " + quoted_value(value.dump()));
    return x;
  }
  std::optional<double> number(const json& in, const std::string& key,
                               const std::string& prefix = "", bool whole = false) const {
    const json* value = find(in, key);
    if (!value) return std::nullopt;
    return checked(*value, prefix + key, whole);
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
        throw ViewFileError(scenes::printable(path_) + ": unknown entry '" + quoted_value(key) +
                            "'" + where + " (known: " + list + ")");
      }
    }
  }

 private:
  const std::string& path_;
};

constexpr scenes::EnumName<render::ColorBy> kColorNames[] = {
    {render::ColorBy::Subdomain, "subdomain"},
    {render::ColorBy::Strut, "strut"},
    {render::ColorBy::Stress, "stress"},
    {render::ColorBy::Moment, "moment"}};

}  // namespace

const char* color_name(render::ColorBy color) {
  return scenes::name_of(kColorNames, color);
}

std::optional<render::ColorBy> color_from_name(const std::string& name) {
  return scenes::value_named(kColorNames, name);
}

SavedView read_view_file(const std::string& path) {
  std::string text;
  try {
    text = read_input_file(path, "view file");
  } catch (const InputFileError& error) {
    throw ViewFileError(error.what());
  }
  return parse_view(text, path);
}

SavedView parse_view(const std::string& text, const std::string& path) {
  json root;
  try {
    root = parse_json_input(text, path, "view file", [](const std::string& entry) {
      const NumberRange* range = view_range_of(entry);
      return range ? std::string(range->text) : std::string();
    });
  } catch (const InputFileError& error) {
    throw ViewFileError(error.what());
  }
  if (!root.is_object())
    throw ViewFileError(scenes::printable(path) + ": a view file is a JSON object");
  const Reader r(path);
  r.only(root,
         {"fetic_view", "size", "center", "zoom", "magnification", "text_size", "color", "show",
          "scales", "scale_basis"},
         "");
  SavedView view;
  r.number(root, "fetic_view", "", true);
  if (const json* size = r.find(root, "size")) {
    if (!size->is_array() || size->size() != 2)
      r.fail("size", "must be [width, height] in pixels, each 16 to 8192");
    view.width = static_cast<int>(r.checked((*size)[0], "size[0]", true));
    view.height = static_cast<int>(r.checked((*size)[1], "size[1]", true));
  }
  if (const json* center = r.find(root, "center")) {
    if (!center->is_array() || center->size() != 2)
      r.fail("center", "must be [x, y] in the scene's length unit");
    view.center_x = r.checked((*center)[0], "center[0]");
    view.center_y = r.checked((*center)[1], "center[1]");
  }
  view.zoom = r.number(root, "zoom");
  view.text_size = r.number(root, "text_size");
  if (const json* basis = r.find(root, "scale_basis")) {
    if (!basis->is_string() || basis->get<std::string>().size() > 60 ||
        scenes::printable(basis->get<std::string>()) != basis->get<std::string>())
      r.fail("scale_basis", "must be a short line of text such as \"over loads 0-2\"");
    view.scale_basis = basis->get<std::string>();
  }
  // "auto" (or 0, as older files have it): chosen from the scales, as the window does.
  if (const json* m = r.find(root, "magnification"))
    view.magnification = (m->is_string() && m->get<std::string>() == "auto") ||
                                 (m->is_number() && m->get<double>() == 0.0)
                             ? 0.0
                             : r.checked(*m, "magnification");
  if (const json* color = r.find(root, "color")) {
    view.color_by = color_from_name(color->is_string() ? color->get<std::string>() : "");
    if (!view.color_by)
      r.fail("color", "must be \"subdomain\", \"stress\", \"strut\" or \"moment\"");
  }
  if (const json* show = r.find(root, "show")) {
    if (!show->is_object()) r.fail("show", "must be an object of true/false toggles");
    r.only(*show, {"forces", "gaps", "overlay", "labels", "corners"}, " in 'show'");
    view.forces = r.boolean(*show, "forces");
    view.gaps = r.boolean(*show, "gaps");
    view.overlay = r.boolean(*show, "overlay");
    view.labels = r.boolean(*show, "labels");
    view.corners = r.boolean(*show, "corners");
  }
  if (const json* scales = r.find(root, "scales")) {
    if (!scales->is_object()) r.fail("scales", "must be an object");
    r.only(*scales,
           {"displacement", "force", "stress", "moment", "iterations", "active_set", "residual_low",
            "residual_high", "stretch", "lateral"},
           " in 'scales'");
    const auto scale = [&](const char* key, bool whole = false) {
      return r.number(*scales, key, "scales.", whole).value_or(0.0);
    };
    render::RunExtent extent;
    extent.largest_displacement = scale("displacement");
    extent.largest_force = scale("force");
    extent.largest_stress = scale("stress");
    extent.largest_moment = scale("moment");
    extent.largest_iteration = static_cast<int>(scale("iterations", true));
    extent.largest_active_set = static_cast<int>(scale("active_set", true));
    extent.smallest_residual = scale("residual_low");
    extent.largest_residual = scale("residual_high");
    extent.largest_stretch = scale("stretch");
    if (const json* lateral = r.find(*scales, "lateral")) {
      if (!lateral->is_array())
        r.fail("scales.lateral", "must be a list of numbers, one per strut");
      for (std::size_t i = 0; i < lateral->size(); ++i)
        extent.strut_lateral.push_back(
            r.checked((*lateral)[i], "scales.lateral[" + std::to_string(i) + "]"));
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
  if (view.magnification) {
    if (*view.magnification > 0.0)
      root["magnification"] = *view.magnification;
    else
      root["magnification"] = "auto";
  }
  if (view.text_size) root["text_size"] = *view.text_size;
  if (view.scale_basis) root["scale_basis"] = *view.scale_basis;
  if (view.color_by) root["color"] = color_name(*view.color_by);
  nlohmann::ordered_json show = nlohmann::ordered_json::object();
  if (view.forces) show["forces"] = *view.forces;
  if (view.gaps) show["gaps"] = *view.gaps;
  if (view.overlay) show["overlay"] = *view.overlay;
  if (view.labels) show["labels"] = *view.labels;
  if (view.corners) show["corners"] = *view.corners;
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
  if (saved.corners) view.show_corners = *saved.corners;
  if (saved.zoom) view.zoom = *saved.zoom;
  if (saved.text_size) view.min_text_size = static_cast<float>(*saved.text_size);
  if (saved.center_x && saved.center_y) {
    view.centered = true;
    view.center_x = *saved.center_x;
    view.center_y = *saved.center_y;
  }
}

std::optional<SavedView> read_view_or_report(const std::string& path, int& status) {
  if (path.empty()) return SavedView{};
  try {
    return read_view_file(path);
  } catch (const ViewFileError& error) {
    std::cerr << error.what() << '\n';
    status = interrupted() ? kExitInterrupted : kExitUsage;
    return std::nullopt;
  }
}

void apply_scales(const std::optional<render::RunExtent>& scales, render::RunExtent& extent) {
  if (!scales) return;
  // The saved scales are all of a RunExtent but the run's own record, which stays.
  render::RunExtent scaled = *scales;
  scaled.frame_count = extent.frame_count;
  scaled.zero_residual = extent.zero_residual;
  scaled.steps = std::move(extent.steps);
  scaled.final_status = extent.final_status;
  scaled.final_message = std::move(extent.final_message);
  extent = std::move(scaled);
}

}  // namespace fetic::app
