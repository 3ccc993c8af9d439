#include "app/vtu_export.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <system_error>
#include <utility>

#include "app/output_file.hpp"
#include "app/version.hpp"
#include "scenes/units.hpp"
#include "solver/element_results.hpp"

namespace fetic::app {
namespace {

std::vector<VtkArray> state_field_data(const solver::Snapshot& state) {
  return {VtkArray{"load_factor", 1, std::vector<double>{state.load_factor}},
          VtkArray{"iteration", 1, std::vector<std::int32_t>{state.iteration}},
          VtkArray{"residual", 1, std::vector<double>{state.residual}},
          VtkArray{"converged", 1,
                   std::vector<std::uint8_t>{state.status == solver::Status::Converged}}};
}

// What wrote the file and the units of its values (the scene's own).
std::vector<std::pair<std::string, std::string>> field_text(const solver::Model& model) {
  return {{"fetic_version", fetic_version()},
          {"length_unit", model.units.length},
          {"force_unit", model.units.force},
          {"stress_unit", scenes::stress_unit(model.units)}};
}

void add_point(VtkGrid& grid, std::vector<double>& displacement, const solver::Vec2& x,
               const solver::Vec2& u) {
  grid.points.insert(grid.points.end(), {x.x(), x.y(), 0.0});
  displacement.insert(displacement.end(), {u.x(), u.y(), 0.0});
}

// Adds an entry to the .pvd written for the previous frame, in place: its closing lines
// are overwritten by the entry and them again, so the file is complete after every frame
// and a series of N frames costs N entries written, not N^2 (4,000 load steps took 28 s
// when the whole file was rewritten each time). False, with nothing changed, when the file
// does not end as this series left it (it is then written whole).
bool append_pvd(const std::string& path, const PvdEntry& entry) {
  const std::string closing = kPvdClosing;
  std::fstream file(current_version_of(path), std::ios::in | std::ios::out | std::ios::binary);
  if (!file) return false;
  file.seekg(0, std::ios::end);
  const std::streamoff size = file.tellg();
  if (size < static_cast<std::streamoff>(closing.size())) return false;
  std::string tail(closing.size(), '\0');
  file.seekg(size - static_cast<std::streamoff>(closing.size()));
  if (!file.read(tail.data(), static_cast<std::streamsize>(tail.size())) || tail != closing)
    return false;
  file.seekp(size - static_cast<std::streamoff>(closing.size()));
  file << pvd_entry(entry) << closing;
  file.flush();
  if (!file)
    throw OutputError(path + ": cannot add the frame to the ParaView collection (" +
                      std::strerror(errno) + ")");
  return true;
}

// Per strut node, its point in the grid: one per node, except that the ends a joint joins
// share the point of the end met first (strut order) - so ParaView sees a frame as one
// connected piece. `first_end` marks the nodes that made their point.
std::vector<std::vector<std::int64_t>> point_numbers(const solver::Model& model,
                                                     std::vector<std::vector<char>>& first_end) {
  std::map<std::pair<int, int>, size_t> joint_of_end;
  for (size_t j = 0; j < model.joints.size(); ++j)
    for (const auto& end : model.joints[j].ends)
      joint_of_end[end] = j;
  std::vector<std::int64_t> joint_point(model.joints.size(), -1);
  std::vector<std::vector<std::int64_t>> point(model.struts.size());
  first_end.assign(model.struts.size(), {});
  std::int64_t next = 0;
  for (size_t s = 0; s < model.struts.size(); ++s) {
    const int count = model.struts[s].node_count();
    point[s].assign(static_cast<size_t>(count), -1);
    first_end[s].assign(static_cast<size_t>(count), 1);
    for (int n = 0; n < count; ++n) {
      const auto joint = joint_of_end.find({static_cast<int>(s), n});
      std::int64_t& shared = joint == joint_of_end.end() ? point[s][static_cast<size_t>(n)]
                                                         : joint_point[joint->second];
      if (shared < 0)
        shared = next++;
      else
        first_end[s][static_cast<size_t>(n)] = 0;
      point[s][static_cast<size_t>(n)] = shared;
    }
  }
  return point;
}

// Frame struts: per element the rotations and bending moments at both of its ends (node
// i, xi = 0, and node i + 1, xi = 1), so that the ends of a pinned joint keep their own
// rotations and the moment's linear course along each element is there in full.
void add_frame_cell_data(const solver::Model& model, const solver::Snapshot& state, VtkGrid& grid) {
  const auto rotations = solver::strut_rotations(model, state);
  const auto moments = solver::strut_moments(model, state);
  std::vector<double> end_rotations, end_moments;
  for (size_t s = 0; s < model.struts.size(); ++s) {
    const int elements = model.struts[s].node_count() - 1;
    for (int k = 0; k < elements; ++k) {
      const auto at = static_cast<size_t>(k);
      end_rotations.insert(end_rotations.end(), {rotations[s][at], rotations[s][at + 1]});
      const bool known = s < moments.size() && !moments[s].empty();
      end_moments.insert(end_moments.end(), {known ? moments[s].at(k, 0.0) : 0.0,
                                             known ? moments[s].at(k, 1.0) : 0.0});
    }
  }
  grid.cell_data.push_back(VtkArray{"end_rotations", 2, std::move(end_rotations)});
  grid.cell_data.push_back(VtkArray{"bending_moment_ends", 2, std::move(end_moments)});
}

}  // namespace

VtkGrid struts_grid(const solver::Model& model, const solver::Snapshot& state) {
  VtkGrid grid;
  const auto u = solver::strut_displacements(model, state);
  const auto elements = solver::element_results(model, state);
  const bool frame = model.frame();
  const auto rotations =
      frame ? solver::strut_rotations(model, state) : std::vector<std::vector<double>>{};
  std::vector<std::vector<char>> first_end;
  const auto point_of = point_numbers(model, first_end);
  std::vector<double> displacement, rotation;
  std::vector<std::int32_t> strut_ids, element_ids, subdomains;
  std::vector<VtkArray> fields;  // stress_* and resultants, concatenated over struts
  for (size_t s = 0; s < model.struts.size(); ++s) {
    const solver::StrutMesh& mesh = model.struts[s];
    for (int n = 0; n < mesh.node_count(); ++n) {
      const auto at = static_cast<size_t>(n);
      if (!first_end[s][at]) continue;  // a joint's point, made by an earlier end
      add_point(grid, displacement, mesh.nodes[at], u[s][at]);
      if (frame) rotation.push_back(rotations[s][at]);
    }
    const solver::StrutElements& e = elements[s];
    for (int k = 0; k < e.element_count(); ++k) {
      for (int a = 0; a < e.nodes_per_element; ++a)
        grid.connectivity.push_back(point_of[s][static_cast<size_t>(
            e.connectivity[static_cast<size_t>(k * e.nodes_per_element + a)])]);
      grid.offsets.push_back(static_cast<std::int64_t>(grid.connectivity.size()));
      grid.types.push_back(e.nodes_per_element == 4 ? kVtkQuad : kVtkLine);
      strut_ids.push_back(static_cast<std::int32_t>(s));
      element_ids.push_back(k);
      subdomains.push_back(e.subdomain[static_cast<size_t>(k)]);
    }
    // Every strut of a model has the same fields in the same order.
    std::vector<std::pair<std::string, const std::vector<double>*>> named;
    for (const solver::NamedValues& field : e.stress)
      named.emplace_back("stress_" + field.name, &field.values);
    for (const solver::NamedValues& field : e.resultants)
      named.emplace_back(field.name, &field.values);
    if (fields.empty())
      for (const auto& [name, values] : named)
        fields.push_back(VtkArray{name, 1, std::vector<double>{}});
    for (size_t f = 0; f < named.size() && f < fields.size(); ++f) {
      auto& target = std::get<std::vector<double>>(fields[f].values);
      target.insert(target.end(), named[f].second->begin(), named[f].second->end());
    }
  }
  grid.point_data.push_back(VtkArray{"displacement", 3, std::move(displacement)});
  if (frame) grid.point_data.push_back(VtkArray{"rotation", 1, std::move(rotation)});
  grid.cell_data.push_back(VtkArray{"strut", 1, std::move(strut_ids)});
  grid.cell_data.push_back(VtkArray{"element", 1, std::move(element_ids)});
  grid.cell_data.push_back(VtkArray{"subdomain", 1, std::move(subdomains)});
  for (VtkArray& field : fields)
    grid.cell_data.push_back(std::move(field));
  if (frame) add_frame_cell_data(model, state, grid);
  grid.field_data = state_field_data(state);
  grid.field_text = field_text(model);
  return grid;
}

VtkGrid contacts_grid(const solver::Model& model, const solver::Snapshot& state) {
  VtkGrid grid;
  const auto u = solver::strut_displacements(model, state);
  std::vector<double> displacement, gap, force, normal;
  std::vector<std::int32_t> contact, pair_index;
  std::vector<std::uint8_t> active;
  for (size_t p = 0; p < model.pairs.size(); ++p) {
    const solver::ContactPair& pair = model.pairs[p];
    const auto a = static_cast<size_t>(pair.strut_a), b = static_cast<size_t>(pair.strut_b);
    add_point(grid, displacement, model.struts[a].nodes[static_cast<size_t>(pair.node_a)],
              u[a][static_cast<size_t>(pair.node_a)]);
    add_point(grid, displacement, model.struts[b].nodes[static_cast<size_t>(pair.node_b)],
              u[b][static_cast<size_t>(pair.node_b)]);
    grid.connectivity.insert(grid.connectivity.end(), {static_cast<std::int64_t>(2 * p),
                                                       static_cast<std::int64_t>(2 * p + 1)});
    grid.offsets.push_back(static_cast<std::int64_t>(grid.connectivity.size()));
    grid.types.push_back(kVtkLine);
    contact.push_back(pair.contact);
    pair_index.push_back(pair.pair);
    gap.push_back(pair.gap);
    force.push_back(p < state.force.size() ? state.force[p] : 0.0);
    active.push_back(p < state.in_working_set.size() && state.in_working_set[p] ? 1 : 0);
    normal.insert(normal.end(), {pair.normal.x(), pair.normal.y(), 0.0});
  }
  grid.point_data.push_back(VtkArray{"displacement", 3, std::move(displacement)});
  grid.cell_data.push_back(VtkArray{"contact", 1, std::move(contact)});
  grid.cell_data.push_back(VtkArray{"pair", 1, std::move(pair_index)});
  grid.cell_data.push_back(VtkArray{"gap", 1, std::move(gap)});
  grid.cell_data.push_back(VtkArray{"force", 1, std::move(force)});
  grid.cell_data.push_back(VtkArray{"active", 1, std::move(active)});
  grid.cell_data.push_back(VtkArray{"normal", 3, std::move(normal)});
  grid.field_data = state_field_data(state);
  grid.field_text = field_text(model);
  return grid;
}

VtuSeries::VtuSeries(std::string directory, const solver::Model& model, VtkEncoding encoding)
    : directory_(std::move(directory)), model_(model), encoding_(encoding) {
  std::error_code error;
  // A link to a folder is followed (a dangling one is refused by check_output_folder).
  std::filesystem::create_directories(resolved_output_path(directory_), error);
  if (error || !std::filesystem::is_directory(directory_))
    throw OutputError(directory_ + ": cannot create the directory for the ParaView files (" +
                      (error ? error.message() : "not a directory") + ")");
}

std::string VtuSeries::file_name(const char* dataset, int index) const {
  char name[64];
  std::snprintf(name, sizeof name, "%s_%04d.vtu", dataset, index);
  return name;
}

void VtuSeries::write(const solver::Snapshot& state, double time) {
  const int index = frames();
  const std::filesystem::path dir(directory_);
  write_output((dir / file_name("struts", index)).string(),
               [&](std::ostream& out) { write_vtu(out, struts_grid(model_, state), encoding_); });
  write_output((dir / file_name("contacts", index)).string(),
               [&](std::ostream& out) { write_vtu(out, contacts_grid(model_, state), encoding_); });
  times_.push_back(time);
  for (const char* dataset : {"struts", "contacts"}) {
    const std::string pvd = (dir / (std::string(dataset) + ".pvd")).string();
    if (index > 0 && append_pvd(pvd, {time, file_name(dataset, index)})) continue;
    std::vector<PvdEntry> entries;
    for (int k = 0; k < frames(); ++k)
      entries.push_back({times_[static_cast<size_t>(k)], file_name(dataset, k)});
    write_output(pvd, [&](std::ostream& out) { write_pvd(out, entries); });
  }
}

}  // namespace fetic::app
