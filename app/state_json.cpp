#include "app/state_json.hpp"

#include <cmath>
#include <memory>

#include "solver/element_results.hpp"

namespace fetic::app {
namespace {

OrderedJson point(const solver::Vec2& p) {
  return OrderedJson::array({p.x(), p.y()});
}

OrderedJson strut_json(const solver::Model& model, int s, const std::vector<solver::Vec2>& u,
                       const solver::StrutElements& elements) {
  const solver::StrutMesh& mesh = model.struts[static_cast<size_t>(s)];
  OrderedJson nodes = OrderedJson::array(), moved = OrderedJson::array();
  for (int n = 0; n < mesh.node_count(); ++n) {
    nodes.push_back(point(mesh.nodes[static_cast<size_t>(n)]));
    moved.push_back(point(u[static_cast<size_t>(n)]));
  }
  OrderedJson connectivity = OrderedJson::array();
  for (int e = 0; e < elements.element_count(); ++e) {
    OrderedJson element = OrderedJson::array();
    for (int a = 0; a < elements.nodes_per_element; ++a)
      element.push_back(
          elements.connectivity[static_cast<size_t>(e * elements.nodes_per_element + a)]);
    connectivity.push_back(std::move(element));
  }
  OrderedJson strut;
  strut["name"] = model.strut_names[static_cast<size_t>(s)];
  strut["nodes"] = std::move(nodes);
  strut["displacements"] = std::move(moved);
  strut["elements"] = std::move(connectivity);
  strut["element_subdomains"] = elements.subdomain;
  OrderedJson stress = OrderedJson::object();
  for (const solver::NamedValues& field : elements.stress)
    stress[field.name] = field.values;
  strut["stress"] = std::move(stress);
  for (const solver::NamedValues& field : elements.resultants)
    strut[field.name] = field.values;
  return strut;
}

// What strut_json(...) (with a frame's rotations) writes through write_streamed, as text:
// the same keys in the same order (the name, the only plain value, first), the same bytes.
void write_strut(JsonText& text, const solver::Model& model, int s,
                 const solver::StrutResults& results, int depth) {
  const solver::StrutMesh& mesh = model.struts[static_cast<size_t>(s)];
  const std::vector<solver::Vec2> u = results.displacements(s);
  const solver::StrutElements elements = results.elements(s);
  // The nodes' coordinates recur (JsonText::recurring_number), the displacements hardly.
  const auto points = [&](const std::vector<solver::Vec2>& list, int inner, bool recurring) {
    text.parallel_array(mesh.nodes.size(), inner, [&](JsonText& out, size_t n, int at) {
      out.array(2, at, [&](size_t k, int) {
        const double value = list[n][static_cast<int>(k)];
        recurring ? out.recurring_number(value) : out.number(value);
      });
    });
  };
  const auto numbers = [&](const auto& list, int inner) {
    text.parallel_array(list.size(), inner,
                        [&](JsonText& out, size_t k, int) { out.number(list[k]); });
  };
  const int inner = depth + 1;
  text.raw("{");
  text.member("name", inner, true);
  text.string(model.strut_names[static_cast<size_t>(s)]);
  text.member("nodes", inner, false);
  points(mesh.nodes, inner, true);
  text.member("displacements", inner, false);
  points(u, inner, false);
  text.member("elements", inner, false);
  const auto per = static_cast<size_t>(elements.nodes_per_element);
  text.parallel_array(
      static_cast<size_t>(elements.element_count()), inner, [&](JsonText& out, size_t e, int at) {
        out.array(per, at, [&](size_t a, int) { out.number(elements.connectivity[e * per + a]); });
      });
  text.member("element_subdomains", inner, false);
  numbers(elements.subdomain, inner);
  text.member("stress", inner, false);
  if (elements.stress.empty())
    text.raw("{}");
  else {
    text.raw("{");
    for (size_t f = 0; f < elements.stress.size(); ++f) {
      text.member(elements.stress[f].name, inner + 1, f == 0);
      numbers(elements.stress[f].values, inner + 1);
    }
    text.newline(inner);
    text.raw("}");
  }
  for (const solver::NamedValues& field : elements.resultants) {
    text.member(field.name, inner, false);
    numbers(field.values, inner);
  }
  if (model.frame()) {
    text.member("rotations", inner, false);
    numbers(results.rotations(s), inner);
  }
  text.newline(depth);
  text.raw("}");
}

OrderedJson contact_json(const solver::Model& model, const solver::Snapshot& state, size_t c) {
  OrderedJson pairs = OrderedJson::array();
  double total = 0.0;
  int active_pairs = 0;
  for (int k = model.contact_first_pair[c]; k < model.contact_first_pair[c + 1]; ++k) {
    const auto at = static_cast<size_t>(k);
    const solver::ContactPair& pair = model.pairs[at];
    const bool active = at < state.in_working_set.size() && state.in_working_set[at];
    const double force = at < state.force.size() ? state.force[at] : 0.0;
    total += force;
    active_pairs += active ? 1 : 0;
    OrderedJson item;
    item["gap"] = pair.gap;
    item["force"] = force;
    item["active"] = active;
    item["node_a"] = pair.node_a;
    item["node_b"] = pair.node_b;
    item["point_a"] = point(
        model.struts[static_cast<size_t>(pair.strut_a)].nodes[static_cast<size_t>(pair.node_a)]);
    item["point_b"] = point(
        model.struts[static_cast<size_t>(pair.strut_b)].nodes[static_cast<size_t>(pair.node_b)]);
    item["normal"] = point(pair.normal);
    pairs.push_back(std::move(item));
  }
  OrderedJson contact;
  contact["a"] = model.contact_ends[c].first;
  contact["b"] = model.contact_ends[c].second;
  contact["force"] = total;
  contact["active_pairs"] = active_pairs;
  contact["pairs"] = std::move(pairs);
  return contact;
}

OrderedJson reactions_json(const solver::Model& model, const solver::Snapshot& state) {
  OrderedJson reactions = OrderedJson::array();
  for (const solver::SupportReaction& reaction : solver::support_reactions(model, state)) {
    OrderedJson node_forces = OrderedJson::array();
    for (const solver::Vec2& f : reaction.node_forces)
      node_forces.push_back(point(f));
    OrderedJson item;
    item["support"] = end_label(model, reaction.strut, reaction.end);
    item["force"] = point(reaction.force);
    item["nodes"] = reaction.nodes;
    item["node_forces"] = std::move(node_forces);
    reactions.push_back(std::move(item));
  }
  return reactions;
}

}  // namespace

std::string end_label(const solver::Model& model, int strut, scenes::StrutEnd end) {
  return model.strut_names[static_cast<size_t>(strut)] + "." + scenes::to_string(end);
}

void add_state(OrderedJson& out, const solver::Model& model, const solver::Snapshot& state,
               StreamedParts* streamed) {
  const bool interrupted = state.status == solver::Status::Running;
  out["load_factor"] = state.load_factor;
  out["converged"] = state.status == solver::Status::Converged;
  out["interrupted"] = interrupted;
  out["status"] = interrupted ? "interrupted" : solver::to_string(state.status);
  if (!state.message.empty()) out["message"] = state.message;
  out["iterations"] = state.iteration;
  out["residual"] = state.residual;
  out["active_pairs"] = state.active_set_size();

  // One strut's results at a time: the writer runs as the file is written (json_stream.hpp).
  auto results = std::make_shared<solver::StrutResults>(model, state);
  OrderedJson struts = OrderedJson::array();
  if (streamed) {
    const int writer = static_cast<int>(streamed->writers.size());
    streamed->writers.push_back([&model, results](JsonText& text, int s, int depth) {
      write_strut(text, model, s, *results, depth);
    });
    for (size_t s = 0; s < model.struts.size(); ++s)
      struts.push_back(written(writer, static_cast<int>(s)));
  } else {
    for (size_t s = 0; s < model.struts.size(); ++s) {
      const int k = static_cast<int>(s);
      OrderedJson strut = strut_json(model, k, results->displacements(k), results->elements(k));
      if (model.frame()) strut["rotations"] = results->rotations(k);
      struts.push_back(std::move(strut));
    }
  }
  out["struts"] = std::move(struts);

  OrderedJson contacts = OrderedJson::array();
  for (size_t c = 0; c + 1 < model.contact_first_pair.size(); ++c)
    contacts.push_back(contact_json(model, state, c));
  out["contacts"] = std::move(contacts);
  out["reactions"] = reactions_json(model, state);
}

OrderedJson history_json(const std::vector<solver::HistoryEntry>& history) {
  OrderedJson entries = OrderedJson::array();
  for (const solver::HistoryEntry& entry : history) {
    OrderedJson item;
    item["iteration"] = entry.iteration;
    item["residual"] = entry.residual;
    item["active_set"] = entry.active_set;
    if (!std::isnan(entry.error)) item["error"] = entry.error;
    if (entry.f_applications >= 0) item["f_applications"] = entry.f_applications;
    entries.push_back(std::move(item));
  }
  return entries;
}

}  // namespace fetic::app
