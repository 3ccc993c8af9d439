#include "app/vtu_export.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <system_error>
#include <utility>

#include "app/output_file.hpp"
#include "app/version.hpp"
#include "scenes/units.hpp"
#include "solver/element_results.hpp"
#include "solver/huge_pages.hpp"

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
// connected piece. Made per strut when asked (only joint ends are kept for all struts).
class PointNumbers {
 public:
  explicit PointNumbers(const solver::Model& model) {
    std::map<std::pair<int, int>, size_t> joint_of_end;  // in (strut, node) order
    for (size_t j = 0; j < model.joints.size(); ++j)
      for (const auto& end : model.joints[j].ends)
        joint_of_end[end] = j;
    std::vector<std::int64_t> joint_point(model.joints.size(), -1);
    shared_.resize(model.struts.size());
    auto end = joint_of_end.begin();
    std::int64_t next = 0;
    for (size_t s = 0; s < model.struts.size(); ++s) {
      first_.push_back(next);
      counts_.push_back(model.struts[s].node_count());
      std::int64_t skipped = 0;  // ends of this strut that share an earlier end's point
      for (; end != joint_of_end.end() && end->first.first == static_cast<int>(s); ++end) {
        std::int64_t& point = joint_point[end->second];
        if (point >= 0) {
          shared_[s].push_back({end->first.second, point});
          ++skipped;
        } else {
          point = next + end->first.second - skipped;
        }
      }
      next += counts_.back() - skipped;
    }
    points_ = next;
  }
  std::int64_t points() const { return points_; }
  // Per node of the strut its point; `makes` marks the nodes that make theirs.
  std::vector<std::int64_t> strut_points(int strut, std::vector<char>& makes) const {
    const auto s = static_cast<size_t>(strut);
    std::vector<std::int64_t> point(static_cast<size_t>(counts_[s]), 0);
    makes.assign(point.size(), 1);
    std::int64_t next = first_[s];
    size_t e = 0;
    for (size_t n = 0; n < point.size(); ++n) {
      if (e < shared_[s].size() && shared_[s][e].first == static_cast<int>(n)) {
        point[n] = shared_[s][e++].second;
        makes[n] = 0;
      } else {
        point[n] = next++;
      }
    }
    return point;
  }

 private:
  std::vector<std::int64_t> first_, counts_;  // per strut: its first point, its nodes
  std::vector<std::vector<std::pair<int, std::int64_t>>> shared_;  // (node, earlier point)
  std::int64_t points_ = 0;
};

// Makes an array strut by strut: fill(s, values) appends strut s's values.
template <typename T, typename Fill>
VtkStreamedArray per_strut(std::string name, int components, std::size_t values, size_t struts,
                           Fill fill) {
  VtkStreamedArray array{std::move(name), components, values, {}};
  array.make = std::function<void(const VtkSink<T>&)>([struts, fill](const VtkSink<T>& put) {
    std::vector<T> chunk;
    for (size_t s = 0; s < struts; ++s) {
      chunk.clear();
      fill(static_cast<int>(s), chunk);
      put(chunk.data(), chunk.size());
    }
  });
  return array;
}

// What the struts' arrays are made from, shared by their makers.
struct StrutSource {
  StrutSource(const solver::Model& of_model, const solver::Snapshot& of_state, bool hold)
      : model(of_model),
        state(of_state),
        results(of_model, of_state),
        numbers(of_model),
        hold_fields(hold) {
    for (size_t s = 0; s < model.struts.size(); ++s) {
      const solver::StrutElements shape = results.shape(static_cast<int>(s));
      elements.push_back(shape.element_count());
      nodes_per_element.push_back(shape.nodes_per_element);
      cells += static_cast<std::size_t>(shape.element_count());
      corners += shape.connectivity.size();
      if (s > 0) continue;
      const solver::StrutElements topology = results.topology(0);
      for (const solver::NamedValues& field : topology.stress)
        fields.push_back("stress_" + field.name);
      for (const solver::NamedValues& field : topology.resultants)
        fields.push_back(field.name);
      stress_fields = topology.stress.size();
    }
    held.resize(fields.size(), std::vector<Held>(model.struts.size()));
    holds.resize(fields.size(), std::vector<char>(model.struts.size(), 0));
  }
  // Cell field f (stress_* then the resultants) of strut s. Recovering a strut's elements
  // makes all its fields at once, and the arrays ask for them one field after the other:
  // with hold_fields the first asks once and the strut's later fields are held until their
  // arrays take them (up to 5 values per element: 190 MB at 1e7 unknowns, so only for a
  // frame written where that memory is free); without, each array recovers them again.
  // The held values are copies in huge pages (solver/huge_pages.hpp): they are the frame's
  // only fresh memory of that size (the recovered strut's arrays, freed after the copy,
  // serve the next strut), and 4 KiB pages first touched cost 10-30 us each on this VM.
  // Into `out` (its room reused from strut to strut).
  void field(size_t f, int s, std::vector<double>& out) {
    const auto at = static_cast<size_t>(s);
    if (holds[f][at]) {
      holds[f][at] = 0;
      out.assign(held[f][at].begin(), held[f][at].end());
      Held().swap(held[f][at]);
      return;
    }
    solver::StrutElements e = results.elements(s);
    const auto values = [&](size_t g) -> std::vector<double>& {
      return g < stress_fields ? e.stress[g].values : e.resultants[g - stress_fields].values;
    };
    for (size_t g = f + 1; hold_fields && g < fields.size(); ++g) {
      held[g][at].assign(values(g).begin(), values(g).end());
      holds[g][at] = 1;
    }
    out.swap(values(f));
  }
  // Strut s's values of the nodes that make a point.
  template <typename T, typename Value>
  void point_values(int s, std::vector<T>& out, Value value) const {
    std::vector<char> makes;
    numbers.strut_points(s, makes);
    for (size_t n = 0; n < makes.size(); ++n)
      if (makes[n]) value(n, out);
  }

  const solver::Model& model;
  const solver::Snapshot& state;
  solver::StrutResults results;
  PointNumbers numbers;
  std::vector<int> elements;           // per strut
  std::vector<int> nodes_per_element;  // per strut
  std::size_t cells = 0, corners = 0;  // elements, their nodes
  std::vector<std::string> fields;     // stress_* then the resultants, as every strut has them
  size_t stress_fields = 0;
  bool hold_fields = false;
  using Held = solver::huge_pages::Vector<double>;
  std::vector<std::vector<Held>> held;   // [field][strut], see field()
  std::vector<std::vector<char>> holds;  // [field][strut]: held[f][s] is there
};

// Frame struts: per element the rotations and bending moments at both of its ends (node
// i, xi = 0, and node i + 1, xi = 1), so that the ends of a pinned joint keep their own
// rotations and the moment's linear course along each element is there in full.
void add_frame_cell_data(const std::shared_ptr<StrutSource>& source, VtkStreamedGrid& grid) {
  const solver::Model& model = source->model;
  grid.cell_data.push_back(per_strut<double>(
      "end_rotations", 2, 2 * source->cells, model.struts.size(),
      [source](int s, std::vector<double>& out) {
        const std::vector<double> rotations = source->results.rotations(s);
        for (int k = 0; k < source->elements[static_cast<size_t>(s)]; ++k)
          out.insert(out.end(),
                     {rotations[static_cast<size_t>(k)], rotations[static_cast<size_t>(k) + 1]});
      }));
  // A frame's struts are few and short: their moments are made at once.
  auto moments = std::make_shared<std::vector<solver::BeamMoments>>();
  grid.cell_data.push_back(
      per_strut<double>("bending_moment_ends", 2, 2 * source->cells, model.struts.size(),
                        [source, moments](int s, std::vector<double>& out) {
                          if (moments->empty())
                            *moments = solver::strut_moments(source->model, source->state);
                          const auto at = static_cast<size_t>(s);
                          const bool known = at < moments->size() && !(*moments)[at].empty();
                          for (int k = 0; k < source->elements[at]; ++k)
                            out.insert(out.end(), {known ? (*moments)[at].at(k, 0.0) : 0.0,
                                                   known ? (*moments)[at].at(k, 1.0) : 0.0});
                        }));
}

void add_cell_data(const std::shared_ptr<StrutSource>& source, VtkStreamedGrid& grid) {
  const size_t struts = source->model.struts.size();
  const std::size_t cells = source->cells;
  grid.cell_data.push_back(
      per_strut<std::int32_t>("strut", 1, cells, struts, [source](int s, auto& out) {
        out.assign(static_cast<size_t>(source->elements[static_cast<size_t>(s)]), s);
      }));
  grid.cell_data.push_back(
      per_strut<std::int32_t>("element", 1, cells, struts, [source](int s, auto& out) {
        for (int k = 0; k < source->elements[static_cast<size_t>(s)]; ++k)
          out.push_back(k);
      }));
  grid.cell_data.push_back(
      per_strut<std::int32_t>("subdomain", 1, cells, struts, [source](int s, auto& out) {
        const std::vector<int> subdomains = source->results.shape(s).subdomain;
        out.assign(subdomains.begin(), subdomains.end());
      }));
  for (size_t f = 0; f < source->fields.size(); ++f)
    grid.cell_data.push_back(per_strut<double>(
        source->fields[f], 1, cells, struts,
        [source, f](int s, std::vector<double>& out) { source->field(f, s, out); }));
}

void add_cells(const std::shared_ptr<StrutSource>& source, VtkStreamedGrid& grid) {
  const size_t struts = source->model.struts.size();
  grid.connectivity = per_strut<std::int64_t>(
      "connectivity", 1, source->corners, struts, [source](int s, auto& out) {
        std::vector<char> makes;
        const std::vector<std::int64_t> point = source->numbers.strut_points(s, makes);
        for (int node : source->results.shape(s).connectivity)
          out.push_back(point[static_cast<size_t>(node)]);
      });
  auto end = std::make_shared<std::int64_t>(0);  // the running offset
  grid.offsets =
      per_strut<std::int64_t>("offsets", 1, source->cells, struts, [source, end](int s, auto& out) {
        if (s == 0) *end = 0;
        const auto at = static_cast<size_t>(s);
        for (int k = 0; k < source->elements[at]; ++k)
          out.push_back(*end += source->nodes_per_element[at]);
      });
  grid.types =
      per_strut<std::uint8_t>("types", 1, source->cells, struts, [source](int s, auto& out) {
        const std::uint8_t type =
            source->nodes_per_element[static_cast<size_t>(s)] == 4 ? kVtkQuad : kVtkLine;
        out.assign(static_cast<size_t>(source->elements[static_cast<size_t>(s)]), type);
      });
}

}  // namespace

VtkStreamedGrid struts_grid(const solver::Model& model, const solver::Snapshot& state,
                            bool hold_fields) {
  auto source = std::make_shared<StrutSource>(model, state, hold_fields);
  const size_t struts = model.struts.size();
  VtkStreamedGrid grid;
  grid.points = static_cast<std::size_t>(source->numbers.points());
  grid.cells = source->cells;
  grid.point_data.push_back(per_strut<double>(
      "displacement", 3, 3 * grid.points, struts, [source](int s, std::vector<double>& out) {
        const std::vector<solver::Vec2> u = source->results.displacements(s);
        source->point_values(s, out, [&](size_t n, std::vector<double>& values) {
          values.insert(values.end(), {u[n].x(), u[n].y(), 0.0});
        });
      }));
  if (model.frame())
    grid.point_data.push_back(per_strut<double>(
        "rotation", 1, grid.points, struts, [source](int s, std::vector<double>& out) {
          const std::vector<double> rotations = source->results.rotations(s);
          source->point_values(s, out, [&](size_t n, std::vector<double>& values) {
            values.push_back(rotations[n]);
          });
        }));
  add_cell_data(source, grid);
  if (model.frame()) add_frame_cell_data(source, grid);
  grid.coordinates = per_strut<double>(
      "Points", 3, 3 * grid.points, struts, [source](int s, std::vector<double>& out) {
        const solver::StrutMesh& mesh = source->model.struts[static_cast<size_t>(s)];
        source->point_values(s, out, [&](size_t n, std::vector<double>& values) {
          values.insert(values.end(), {mesh.nodes[n].x(), mesh.nodes[n].y(), 0.0});
        });
      });
  add_cells(source, grid);
  grid.field_data = state_field_data(state);
  grid.field_text = field_text(model);
  return grid;
}

VtkGrid contacts_grid(const solver::Model& model, const solver::Snapshot& state) {
  // The pairs' end displacements, read strut by strut (not every strut's nodes at once).
  std::vector<std::vector<size_t>> pairs_of(model.struts.size());
  for (size_t p = 0; p < model.pairs.size(); ++p) {
    pairs_of[static_cast<size_t>(model.pairs[p].strut_a)].push_back(p);
    pairs_of[static_cast<size_t>(model.pairs[p].strut_b)].push_back(p);
  }
  std::vector<solver::Vec2> end_a(model.pairs.size()), end_b(model.pairs.size());
  const solver::StrutResults results(model, state);
  for (size_t s = 0; s < model.struts.size(); ++s) {
    if (pairs_of[s].empty()) continue;
    const std::vector<solver::Vec2> u = results.displacements(static_cast<int>(s));
    for (size_t p : pairs_of[s]) {
      const solver::ContactPair& pair = model.pairs[p];
      if (static_cast<size_t>(pair.strut_a) == s) end_a[p] = u[static_cast<size_t>(pair.node_a)];
      if (static_cast<size_t>(pair.strut_b) == s) end_b[p] = u[static_cast<size_t>(pair.node_b)];
    }
  }
  VtkGrid grid;
  std::vector<double> displacement, gap, force, normal;
  std::vector<std::int32_t> contact, pair_index;
  std::vector<std::uint8_t> active;
  for (size_t p = 0; p < model.pairs.size(); ++p) {
    const solver::ContactPair& pair = model.pairs[p];
    const auto a = static_cast<size_t>(pair.strut_a), b = static_cast<size_t>(pair.strut_b);
    add_point(grid, displacement, model.struts[a].nodes[static_cast<size_t>(pair.node_a)],
              end_a[p]);
    add_point(grid, displacement, model.struts[b].nodes[static_cast<size_t>(pair.node_b)],
              end_b[p]);
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

void VtuSeries::write(const solver::Snapshot& state, double time,
                      const std::function<void(const std::string&)>& progress) {
  const int index = frames();
  const std::filesystem::path dir(directory_);
  const std::string struts = (dir / file_name("struts", index)).string();
  ProgressLine line(progress ? ProgressMode::Never : progress_);
  write_output(struts, [&](std::ostream& out) {
    write_vtu(out, struts_grid(model_, state, hold_fields_), encoding_,
              [&](int written, int arrays) {
                const std::string text = "writing " + struts + ": " + std::to_string(written) +
                                         " of " + std::to_string(arrays) + " arrays";
                if (progress)
                  progress(text);
                else if (line.elapsed_seconds() > 1.0)
                  line.update(text);
              });
  });
  line.clear();
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
