// Picking (docs/WINDOW.md, "Picking"): hovering a node or a contact pair of the picture
// shows its values at the shown iterate in a tooltip; a click pins it to the "Picked"
// window, where its values follow the load and the iteration and can be copied; a pinned
// item is reported in the state file ("picked"). The items under the pointer come from a
// grid over the drawn positions (app/gui/pick_index.hpp), rebuilt with each picture.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include <imgui.h>

#include "app/gui/app.hpp"
#include "render/frame_sequence.hpp"
#include "render/overlay.hpp"
#include "render/scene_framing.hpp"
#include "solver/element_results.hpp"
#include "solver/method.hpp"

namespace fetic::app::gui {
namespace {

constexpr float kPickRadius = 8.0f;  // pixels

// What hovering costs, reported as a "hover" event in the state file after every 200
// frames spent over the picture (docs/WINDOW.md, "Picking"): frames per second while the
// pointer moves over the scene, the pick query's and the index build's time. One window
// per process, so the figures live here rather than in App.
struct HoverStats {
  int frames = 0;
  Clock::time_point first{};
  std::vector<double> query_ms;
  double build_ms = 0.0;  // the last index build
  std::size_t items = 0;
};
HoverStats hover_stats;

double median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  std::nth_element(values.begin(), values.begin() + static_cast<long>(values.size() / 2),
                   values.end());
  return values[values.size() / 2];
}

std::string number(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", x);
  return text;
}

// A frame node's rotation and bending moment, as the result file and the moment colouring
// have them: M of the element before the node (at its end) and of the one after (at its
// start); the two differ where a load or a joint acts on the node.
void frame_node_values(const solver::Model& model, const solver::Snapshot& snapshot,
                       const Pickable& item, nlohmann::json& values) {
  const auto strut = static_cast<std::size_t>(item.a);
  const auto rotations = solver::strut_rotations(model, snapshot);
  if (strut < rotations.size() && static_cast<std::size_t>(item.b) < rotations[strut].size())
    values["rotation"] = rotations[strut][static_cast<std::size_t>(item.b)];
  const auto moments = solver::strut_moments(model, snapshot);
  if (strut >= moments.size() || moments[strut].empty()) return;
  const solver::BeamMoments& m = moments[strut];
  const int last = m.first_element + static_cast<int>(m.ends.size()) - 1;
  nlohmann::json at = nlohmann::json::array();
  if (item.b - 1 >= m.first_element && item.b - 1 <= last) at.push_back(m.at(item.b - 1, 1.0));
  if (item.b >= m.first_element && item.b <= last) at.push_back(m.at(item.b, 0.0));
  values["bending_moment"] = at;  // [after the element before, before the element after]
}

}  // namespace

void App::index_picture(const solver::Snapshot& snapshot, const render::SceneFraming& framing) {
  const auto start = Clock::now();
  const solver::Model& model = *shown_->model;
  const auto displacements = solver::strut_displacements(model, snapshot);
  std::vector<Pickable> items;
  for (std::size_t s = 0; s < model.struts.size(); ++s)
    for (int n = 0; n < model.struts[s].node_count(); ++n)
      items.push_back({Pickable::Kind::Node, static_cast<int>(s), n,
                       framing.node(model, static_cast<int>(s), n,
                                    displacements[s][static_cast<std::size_t>(n)])});
  for (std::size_t k = 0; k < model.pairs.size(); ++k) {
    const solver::ContactPair& pair = model.pairs[k];
    const render::Point a = framing.node(model, pair.strut_a, pair.node_a,
                                         displacements[static_cast<std::size_t>(pair.strut_a)]
                                                      [static_cast<std::size_t>(pair.node_a)]);
    const render::Point b = framing.node(model, pair.strut_b, pair.node_b,
                                         displacements[static_cast<std::size_t>(pair.strut_b)]
                                                      [static_cast<std::size_t>(pair.node_b)]);
    items.push_back(
        {Pickable::Kind::Pair, static_cast<int>(k), 0, {0.5f * (a.x + b.x), 0.5f * (a.y + b.y)}});
  }
  picks_.build(std::move(items), static_cast<float>(view_width_), static_cast<float>(view_height_));
  hover_stats.build_ms = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
  hover_stats.items = picks_.size();
}

nlohmann::json App::pick_values(const Pickable& item) const {
  nlohmann::json values;
  if (!shown_ || shown_->iterates.empty()) return values;
  const solver::Model& model = *shown_->model;
  const solver::Snapshot& snapshot = *shown_->iterates[static_cast<std::size_t>(shown_index())];
  values["load_factor"] = shown_->load_factor;
  values["iteration"] = snapshot.iteration;
  const auto displacement_of = [&](int strut, int node) {
    solver::Vec2 sum = solver::Vec2::Zero();
    int count = 0;
    const solver::StrutMesh& mesh = model.struts[static_cast<std::size_t>(strut)];
    const int i = node / mesh.nodes_across(), k = node % mesh.nodes_across();
    for (const solver::Piece& piece : snapshot.pieces)
      if (piece.strut == strut && piece.box.contains(i, k)) {
        sum += piece.displacement[static_cast<std::size_t>(piece.box.local(i, k))];
        ++count;
      }
    return count > 0 ? solver::Vec2(sum / count) : sum;
  };
  if (item.kind == Pickable::Kind::Node) {
    const solver::StrutMesh& mesh = model.struts[static_cast<std::size_t>(item.a)];
    const solver::Vec2 x = mesh.nodes[static_cast<std::size_t>(item.b)];
    const solver::Vec2 u = displacement_of(item.a, item.b);
    values["kind"] = "node";
    values["strut"] = model.strut_names[static_cast<std::size_t>(item.a)];
    values["strut_index"] = item.a;
    values["node"] = item.b;
    values["position"] = {x.x(), x.y()};
    values["displacement"] = {u.x(), u.y()};
    // The subdomains (pieces of the strut) that hold the node: several on an interface.
    nlohmann::json pieces = nlohmann::json::array();
    const int i = item.b / mesh.nodes_across(), k = item.b % mesh.nodes_across();
    int piece_of_strut = 0;
    for (const solver::Piece& piece : snapshot.pieces) {
      if (piece.strut != item.a) continue;
      if (piece.box.contains(i, k)) pieces.push_back(piece_of_strut);
      ++piece_of_strut;
    }
    values["subdomains"] = pieces;
    if (model.frame()) frame_node_values(model, snapshot, item, values);
  } else {
    const solver::ContactPair& pair = model.pairs[static_cast<std::size_t>(item.a)];
    const solver::Vec2 ua = displacement_of(pair.strut_a, pair.node_a);
    const solver::Vec2 ub = displacement_of(pair.strut_b, pair.node_b);
    const auto k = static_cast<std::size_t>(item.a);
    values["kind"] = "pair";
    values["pair_index"] = item.a;
    values["contact"] = model.contact_labels[static_cast<std::size_t>(pair.contact)];
    values["contact_index"] = pair.contact;
    values["pair"] = pair.pair;
    values["gap"] = pair.gap;
    // (u_a - u_b) . n <= gap: what is left of it now. A closed contact leaves a difference
    // of rounding errors (-1.6e-16 m), which is no penetration: shown as 0.
    const double closing = (ua - ub).dot(pair.normal);
    const double left = pair.gap - closing;
    const double rounding =
        64.0 * std::numeric_limits<double>::epsilon() * (std::abs(pair.gap) + std::abs(closing));
    values["current_gap"] = std::abs(left) <= rounding ? 0.0 : left;
    values["force"] = k < snapshot.force.size() ? snapshot.force[k] : 0.0;
    values["active"] = k < snapshot.in_working_set.size() && snapshot.in_working_set[k] != 0;
    // The rest of what the result file has for a pair (docs/SCENES.md, "Result file").
    const auto point = [](const solver::Vec2& p) { return nlohmann::json::array({p.x(), p.y()}); };
    values["node_a"] = pair.node_a;
    values["node_b"] = pair.node_b;
    values["point_a"] = point(model.struts[static_cast<std::size_t>(pair.strut_a)]
                                  .nodes[static_cast<std::size_t>(pair.node_a)]);
    values["point_b"] = point(model.struts[static_cast<std::size_t>(pair.strut_b)]
                                  .nodes[static_cast<std::size_t>(pair.node_b)]);
    values["normal"] = point(pair.normal);
  }
  return values;
}

std::string App::pick_text(const Pickable& item) const {
  const nlohmann::json v = pick_values(item);
  if (v.empty()) return {};
  const std::string& length = shown_->model->units.length;
  const std::string& force = shown_->model->units.force;
  std::string text;
  if (item.kind == Pickable::Kind::Node) {
    text = "strut " + v["strut"].get<std::string>() + ", node " + std::to_string(item.b) + "\n";
    text += "position      " + number(v["position"][0]) + ", " + number(v["position"][1]) + " " +
            length + "\n";
    text += "displacement  " + number(v["displacement"][0]) + ", " + number(v["displacement"][1]) +
            " " + length + "\n";
    text += "subdomain     ";
    for (const auto& p : v["subdomains"])
      text += std::to_string(p.get<int>()) + " ";
    text += "\n";
    if (v.contains("rotation")) text += "rotation      " + number(v["rotation"]) + " rad\n";
    if (v.contains("bending_moment") && !v["bending_moment"].empty()) {
      const auto& m = v["bending_moment"];
      text += "bending moment " + number(m[0]);
      if (m.size() > 1 && m[1].get<double>() != m[0].get<double>())
        text += " | " + number(m[1]) + " (either side)";
      text += " " + force + " " + length + "\n";
    }
  } else {
    text = "contact " + v["contact"].get<std::string>() + ", pair " +
           std::to_string(v["pair"].get<int>()) + " (#" + std::to_string(item.a) + ")\n";
    text += "gap           " + number(v["gap"]) + " " + length + "\n";
    text += "current gap   " + number(v["current_gap"]) + " " + length + "\n";
    text += "force         " + number(v["force"]) + " " + force + "\n";
    text += std::string("active        ") + (v["active"].get<bool>() ? "yes" : "no") + "\n";
    text += "nodes         " + std::to_string(v["node_a"].get<int>()) + " - " +
            std::to_string(v["node_b"].get<int>()) + "\n";
    text += "normal        " + number(v["normal"][0]) + ", " + number(v["normal"][1]) + "\n";
  }
  text += "load " + number(v["load_factor"]) + ", iteration " +
          std::to_string(v["iteration"].get<int>());
  return text;
}

void App::refresh_pick_index() {
  if (!pick_stale_ || !pick_state_ || pick_state_ != shown_) return;
  index_picture(*pick_state_->iterates[static_cast<std::size_t>(pick_iterate_)], placed_);
  pick_stale_ = false;
}

// The item under the pointer, and every 200 frames over the picture a "hover" event.
void App::hover(render::Point at) {
  const auto start = Clock::now();
  hovered_ = picks_.nearest(at, kPickRadius);
  pick_query_ms_ = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
  if (hover_stats.frames++ == 0) hover_stats.first = start;
  hover_stats.query_ms.push_back(pick_query_ms_);
  if (hover_stats.frames == 201) {
    const double seconds = std::chrono::duration<double>(start - hover_stats.first).count();
    log_.write({{"event", "hover"},
                {"frames", 200},
                {"seconds", seconds},
                {"frames_per_second", seconds > 0.0 ? 200.0 / seconds : 0.0},
                {"query_ms_median", median(hover_stats.query_ms)},
                {"query_ms_max",
                 *std::max_element(hover_stats.query_ms.begin(), hover_stats.query_ms.end())},
                {"index_items", hover_stats.items},
                {"index_build_ms", hover_stats.build_ms}});
    hover_stats = HoverStats{0, {}, {}, hover_stats.build_ms, hover_stats.items};
  }
}

void App::picking(float view_x, float view_width, float view_height) {
  const ImGuiIO& io = ImGui::GetIO();
  const render::Point at{io.MousePos.x - view_x, io.MousePos.y};
  const bool over_picture =
      !io.WantCaptureMouse && at.x >= 0 && at.y >= 0 && at.x < view_width && at.y < view_height;
  const std::optional<Pickable> hovered_before = hovered_;
  hovered_.reset();
  // No hover while the view moves (dragged, or zoomed by the wheel until it rests): every
  // picture would build the index again, a pass over all nodes that on millions of them
  // costs more than the picture. Two methods side by side: the pick index knows the
  // single picture only (its framing), so the comparison has no hover; pinned items stay
  // listed.
  const bool still =
      !ImGui::IsMouseDragging(ImGuiMouseButton_Left) && Clock::now() - view_moved_ >= kViewRest;
  // An index that took more than a few frames to build (millions of nodes) is built again
  // only when the pointer moves, not for every new picture under a resting pointer (a
  // solve shows one per iteration): the item hovered before stays.
  const bool moved = at.x != last_pointer_.x || at.y != last_pointer_.y;
  last_pointer_ = at;
  if (pick_stale_ && !moved && hover_stats.build_ms > kSlowIndexMs) {
    hovered_ = over_picture && still && !comparing() ? hovered_before : std::nullopt;
  } else {
    if ((over_picture || !pinned_.empty()) && still) refresh_pick_index();
    if (over_picture && shown_ && !comparing() && still) hover(at);
  }
  if (hovered_) {
    ImGui::BeginTooltip();
    ImGui::TextUnformatted(pick_text(*hovered_).c_str());
    ImGui::TextDisabled("click: pin");
    ImGui::EndTooltip();
    // A click (not the end of a drag, not a double-click) pins or unpins it.
    if (ImGui::IsMouseReleased(ImGuiMouseButton_Left) &&
        ImGui::GetMouseDragDelta(ImGuiMouseButton_Left, 0.0f).x == 0.0f &&
        ImGui::GetMouseDragDelta(ImGuiMouseButton_Left, 0.0f).y == 0.0f)
      toggle_pin(*hovered_);
  }
  pinned_window(view_x, view_width, view_height);
}

void App::toggle_pin(const Pickable& item) {
  for (std::size_t i = 0; i < pinned_.size(); ++i)
    if (pinned_[i] == item) {
      pinned_.erase(pinned_.begin() + static_cast<std::ptrdiff_t>(i));
      return;
    }
  pinned_.push_back(item);
  nlohmann::json event = pick_values(item);
  event["event"] = "picked";
  log_.write(event);
}

void App::pinned_window(float view_x, float view_width, float view_height) {
  if (pinned_.empty()) return;
  // First shown at the top right of the scene, left of the plots (not over them).
  float right = view_width;
  if (show_overlay_)
    right =
        render::overlay_panel(view(static_cast<int>(view_width), static_cast<int>(view_height))).x0;
  // Below the caption band (the caption is never covered), sized to what it lists, at
  // most as tall as the picture below the caption (then it scrolls).
  const render::View v = view(static_cast<int>(view_width), static_cast<int>(view_height));
  const float below_caption =
      render::scene_region(v).y0 + render::caption_band(render::text_size(v));
  ImGui::SetNextWindowPos(ImVec2(view_x + std::max(0.0f, right - 320.0f), below_caption),
                          ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSizeConstraints(
      ImVec2(0.0f, 0.0f), ImVec2(view_width, std::max(100.0f, view_height - below_caption)));
  ImGui::Begin("Picked", nullptr,
               ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_AlwaysAutoResize);
  if (ImGui::GetWindowPos().y < below_caption)
    ImGui::SetWindowPos(ImVec2(ImGui::GetWindowPos().x, below_caption));
  std::string all;
  int remove = -1;
  for (std::size_t i = 0; i < pinned_.size(); ++i) {
    ImGui::PushID(static_cast<int>(i));
    const std::string text = pick_text(pinned_[i]);
    ImGui::TextUnformatted(text.c_str());
    if (ImGui::SmallButton("copy")) ImGui::SetClipboardText(pick_values(pinned_[i]).dump().c_str());
    ImGui::SameLine();
    if (ImGui::SmallButton("unpin")) remove = static_cast<int>(i);
    ImGui::Separator();
    ImGui::PopID();
    all += pick_values(pinned_[i]).dump() + "\n";
  }
  if (ImGui::Button("copy all (JSON lines)")) ImGui::SetClipboardText(all.c_str());
  ImGui::End();
  if (remove >= 0) pinned_.erase(pinned_.begin() + remove);
}

void App::locate(const std::string& what) {
  // "pair:K" or "node:STRUT:N": where it is drawn, in window pixels (for tests).
  std::string spaced = what;
  std::replace(spaced.begin(), spaced.end(), ':', ' ');
  std::istringstream in(spaced);
  std::string kind;
  Pickable item;
  in >> kind;
  if (kind == "pair") {
    item.kind = Pickable::Kind::Pair;
    in >> item.a;
  } else {
    item.kind = Pickable::Kind::Node;
    in >> item.a >> item.b;
  }
  refresh_pick_index();
  const auto at = picks_.position(item);
  nlohmann::json event{{"event", "located"}, {"what", what}, {"found", at.has_value()}};
  if (at) {
    event["x"] = at->x + panel_width();
    event["y"] = at->y;
  }
  log_.write(event);
}

}  // namespace fetic::app::gui
