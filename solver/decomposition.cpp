#include "solver/decomposition.hpp"

#include <algorithm>
#include <bit>
#include <span>

#include "solver/threads.hpp"

namespace fetic::solver {

std::vector<std::pair<int, int>> split_nodes(int elements, int parts) {
  std::vector<std::pair<int, int>> ranges;
  int first = 0;
  for (int p = 0; p < parts; ++p) {
    // The first (elements % parts) parts get one element more.
    const int size = elements / parts + (p < elements % parts ? 1 : 0);
    ranges.emplace_back(first, first + size);
    first += size;
  }
  return ranges;
}

std::vector<SubdomainPart> parts_of(const Subdomain& sub, int index) {
  if (!sub.parts.empty()) return sub.parts;
  return {SubdomainPart{sub.strut, sub.box, index, {}}};
}

namespace {

// A node's copies: (subdomain, subdomain-local node), in increasing subdomain order.
using CopySpan = std::span<const std::pair<int, int>>;

// A strut's nodes' copies in one flat list, node by node (a vector per node was one
// allocation per node: about 5 million at 1e7 unknowns, in a serial pass).
struct StrutCopyList {
  std::vector<int> first;                 // per node, and one past the last node
  std::vector<std::pair<int, int>> copy;  // node n's: copy[first[n]] .. copy[first[n + 1] - 1]
  CopySpan of_node(int node) const {
    return {copy.data() + first[node], copy.data() + first[node + 1]};
  }
};

// The gluing row u_i - u_j = 0 between copies i and j of one DOF component.
Row gluing_row(CopySpan c, size_t i, size_t j, int dofs_per_node, int comp) {
  Row row;
  row.kind = RowKind::Gluing;
  row.entries = {{c[i].first, c[i].second * dofs_per_node + comp, 1.0},
                 {c[j].first, c[j].second * dofs_per_node + comp, -1.0}};
  row.copies.reserve(c.size());
  for (const auto& [sub, local] : c)
    row.copies.push_back({sub, local * dofs_per_node + comp, 1.0});
  return row;
}

// Gluing rows between every two copies of one DOF component, appended.
void add_gluing_rows(CopySpan c, int dofs_per_node, int comp, Decomposition& d) {
  RedundantGroup group;
  group.copies = static_cast<int>(c.size());
  for (size_t i = 0; i < c.size(); ++i)
    for (size_t j = i + 1; j < c.size(); ++j) {
      group.rows.push_back(static_cast<int>(d.rows.size()));
      group.ends.emplace_back(static_cast<int>(i), static_cast<int>(j));
      d.rows.push_back(gluing_row(c, i, j, dofs_per_node, comp));
    }
  if (group.copies >= 3) d.redundant_groups.push_back(std::move(group));
}

// Where one strut's subdomains, DOFs, modes, gluing rows and redundant groups begin. The
// struts are filled on both cores, each into its own slots: numbered as one strut after
// the other, so every result is the same as filled in turn.
struct StrutStart {
  int subdomain = 0, dof = 0, mode = 0;
  int row = 0, group = 0;
};

// Step 1, per strut: its subdomains (node boxes) into their slots, each node's copies, and
// each node's load on its first copy only.
void place_subdomains(const Model& model, int s, const StrutStart& start, StrutCopyList& copies,
                      Decomposition& d) {
  const StrutMesh& mesh = model.struts[s];
  const auto along = split_nodes(mesh.nx, mesh.subdomains_along);
  const auto across = mesh.ny > 0 ? split_nodes(mesh.ny, mesh.subdomains_across)
                                  : std::vector<std::pair<int, int>>{{0, 0}};
  // Each node's count of copies first (the boxes overlap in their shared nodes).
  std::vector<int>& first = copies.first;
  first.assign(static_cast<size_t>(mesh.node_count()) + 1, 0);
  for (const auto& [i0, i1] : along)
    for (const auto& [k0, k1] : across)
      for (int i = i0; i <= i1; ++i)
        for (int k = k0; k <= k1; ++k)
          ++first[mesh.node(i, k) + 1];
  for (int node = 0; node < mesh.node_count(); ++node)
    first[node + 1] += first[node];
  copies.copy.resize(static_cast<size_t>(first.back()));
  std::vector<int> next(first.begin(), first.end() - 1);
  int index = start.subdomain, dof = start.dof, mode = start.mode;
  for (const auto& [i0, i1] : along) {
    for (const auto& [k0, k1] : across) {
      Subdomain& sub = d.subdomains[index];
      sub.strut = s;
      sub.box = NodeBox{i0, i1, k0, k1};
      sub.dof_count = sub.box.node_count() * mesh.dofs_per_node;
      sub.dof_offset = dof;
      sub.mode_count = mesh.dofs_per_node == 1 ? 1 : 3;
      sub.mode_offset = mode;
      dof += sub.dof_count;
      mode += sub.mode_count;
      sub.load = Eigen::VectorXd::Zero(sub.dof_count);
      for (int i = i0; i <= i1; ++i)
        for (int k = k0; k <= k1; ++k)
          copies.copy[next[mesh.node(i, k)]++] = {index, sub.box.local(i, k)};
      ++index;
    }
  }
  for (int node = 0; node < mesh.node_count(); ++node) {
    const auto [sub, local] = copies.of_node(node).front();
    for (int c = 0; c < mesh.dofs_per_node; ++c)
      d.subdomains[sub].load(local * mesh.dofs_per_node + c) =
          model.loads[s](node * mesh.dofs_per_node + c);
  }
}

// Per node of strut s, the components no support holds.
std::vector<unsigned> free_components(const Model& model, int s) {
  const StrutMesh& mesh = model.struts[s];
  std::vector<unsigned> held(mesh.node_count(), 0u);
  for (const HeldNode& node : model.held_nodes[s])
    held[node.node] = node.components;
  const unsigned all = (1u << mesh.dofs_per_node) - 1u;
  for (unsigned& mask : held)
    mask = ~mask & all;
  return held;
}

// Strut s's gluing rows and redundant groups, counted as glue_strut_copies() writes them.
std::pair<int, int> count_gluing_rows(const Model& model, int s, const StrutCopyList& copies) {
  const std::vector<unsigned> free = free_components(model, s);
  int rows = 0, groups = 0;
  for (int node = 0; node < static_cast<int>(free.size()); ++node) {
    const int c = copies.first[node + 1] - copies.first[node];
    const int components = std::popcount(free[node]);
    rows += components * (c * (c - 1) / 2);
    groups += c >= 3 ? components : 0;
  }
  return {rows, groups};
}

// Step 2, per strut: gluing rows between the copies of every node that no support holds,
// into the strut's slots from start.row and start.group on.
void glue_strut_copies(const Model& model, int s, const StrutCopyList& copies,
                       const StrutStart& start, Decomposition& d) {
  const StrutMesh& mesh = model.struts[s];
  const std::vector<unsigned> free = free_components(model, s);
  int row = start.row, group_at = start.group;
  for (int node = 0; node < mesh.node_count(); ++node) {
    const CopySpan c = copies.of_node(node);
    // Fully redundant: one row per pair of copies (at a cross point of four subdomains
    // six rows, not three), which the scaled Dirichlet preconditioner needs to stay
    // effective there.
    for (int comp = 0; comp < mesh.dofs_per_node; ++comp) {
      if (!(free[node] >> comp & 1u)) continue;
      RedundantGroup group;
      group.copies = static_cast<int>(c.size());
      for (size_t i = 0; i < c.size(); ++i)
        for (size_t j = i + 1; j < c.size(); ++j) {
          group.rows.push_back(row);
          group.ends.emplace_back(static_cast<int>(i), static_cast<int>(j));
          d.rows[row++] = gluing_row(c, i, j, mesh.dofs_per_node, comp);
        }
      if (group.copies >= 3) d.redundant_groups[group_at++] = std::move(group);
    }
  }
}

// The rows after the struts' gluing rows, at most (joints, Dirichlet, contact rows): room
// for all rows at once, not the gluing rows copied when the others are appended.
size_t rows_after_gluing(const Model& model, const std::vector<StrutCopyList>& copies) {
  size_t rows = model.pairs.size();
  for (const JointLink& joint : model.joints) {
    const size_t ends = joint.ends.size();
    rows += static_cast<size_t>(joint.shared) * ends * (ends - 1) / 2;
  }
  for (size_t s = 0; s < model.struts.size(); ++s)
    for (const HeldNode& node : model.held_nodes[s])
      rows +=
          copies[s].of_node(node.node).size() * static_cast<size_t>(std::popcount(node.components));
  return rows;
}

// Steps 1 and 2 on both cores, strut by strut (a serial pass over every node and gluing
// row was 1.6 s of the set-up at 9,679,100 unknowns).
std::vector<StrutCopyList> place_and_glue_struts(const Model& model, Decomposition& d) {
  const int struts = static_cast<int>(model.struts.size());
  std::vector<StrutStart> start(static_cast<size_t>(struts) + 1);
  long long nodes = 0;
  for (int s = 0; s < struts; ++s) {
    const StrutMesh& mesh = model.struts[s];
    const auto along = split_nodes(mesh.nx, mesh.subdomains_along);
    const auto across = mesh.ny > 0 ? split_nodes(mesh.ny, mesh.subdomains_across)
                                    : std::vector<std::pair<int, int>>{{0, 0}};
    StrutStart next = start[s];
    for (const auto& [i0, i1] : along)
      for (const auto& [k0, k1] : across) {
        ++next.subdomain;
        next.dof += NodeBox{i0, i1, k0, k1}.node_count() * mesh.dofs_per_node;
        next.mode += mesh.dofs_per_node == 1 ? 1 : 3;
      }
    start[s + 1] = next;
    nodes += mesh.node_count();
  }
  d.subdomains.resize(static_cast<size_t>(start[struts].subdomain));
  d.total_dofs = start[struts].dof;
  d.total_modes = start[struts].mode;
  std::vector<StrutCopyList> copies(static_cast<size_t>(struts));
  std::vector<std::pair<int, int>> counts(static_cast<size_t>(struts));
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads_for(nodes))
  for (int s = 0; s < struts; ++s) {
    place_subdomains(model, s, start[s], copies[s], d);
    counts[s] = count_gluing_rows(model, s, copies[s]);
  }
  for (int s = 0; s < struts; ++s) {
    start[s + 1].row = start[s].row + counts[s].first;
    start[s + 1].group = start[s].group + counts[s].second;
  }
  d.rows.reserve(static_cast<size_t>(start[struts].row) + rows_after_gluing(model, copies));
  d.rows.resize(static_cast<size_t>(start[struts].row));
  d.redundant_groups.resize(static_cast<size_t>(start[struts].group));
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads_for(nodes))
  for (int s = 0; s < struts; ++s)
    glue_strut_copies(model, s, copies[s], start[s], d);
  return copies;
}

// Step 3 (frame model): joints. The ends' copies of every shared component that no
// support holds, glued like the copies of one node - every pair of ends, so that a joint
// of k ends is a cross point of k subdomains (see decomposition.hpp).
void glue_joints(const Model& model, const std::vector<StrutCopyList>& copies, Decomposition& d) {
  for (const JointLink& joint : model.joints) {
    std::vector<std::pair<int, int>> ends;
    for (const auto& [strut, node] : joint.ends)
      ends.push_back(copies[strut].of_node(node).front());
    const auto [first_strut, first_node] = joint.ends.front();
    for (int comp = 0; comp < joint.shared; ++comp)
      if (!(model.held(first_strut, first_node) >> comp & 1u)) add_gluing_rows(ends, 3, comp, d);
  }
}

// Step 4: Dirichlet rows, one per held component of every copy of a held node.
void hold_dirichlet_nodes(const Model& model, const std::vector<StrutCopyList>& copies,
                          Decomposition& d) {
  for (size_t s = 0; s < model.struts.size(); ++s) {
    const StrutMesh& mesh = model.struts[s];
    for (const HeldNode& node : model.held_nodes[s])
      for (const auto& [sub, local] : copies[s].of_node(node.node))
        for (int comp = 0; comp < mesh.dofs_per_node; ++comp) {
          if (!(node.components >> comp & 1u)) continue;
          Row row;
          row.kind = RowKind::Dirichlet;
          row.entries = {{sub, local * mesh.dofs_per_node + comp, 1.0}};
          d.rows.push_back(std::move(row));
        }
  }
}

// Step 5: a row per contact pair, on the first copy of each side's node (none when both
// sides are held).
void add_contact_rows(const Model& model, const std::vector<StrutCopyList>& copies,
                      Decomposition& d) {
  d.pair_row.assign(model.pairs.size(), -1);
  for (size_t k = 0; k < model.pairs.size(); ++k) {
    const ContactPair& pair = model.pairs[k];
    if (model.translation_held(pair.strut_a, pair.node_a) &&
        model.translation_held(pair.strut_b, pair.node_b))
      continue;
    Row row;
    row.kind = RowKind::Contact;
    row.pair = static_cast<int>(k);
    row.rhs = pair.gap;
    for (const ContactSide& side : contact_sides(model, pair)) {
      const StrutMesh& mesh = model.struts[side.strut];
      const auto [sub, local] = copies[side.strut].of_node(side.node).front();
      for (int comp = 0; comp < mesh.dofs_per_node; ++comp)
        if (side.coefficients(comp) != 0.0)
          row.entries.push_back({sub, local * mesh.dofs_per_node + comp, side.coefficients(comp)});
    }
    d.pair_row[k] = static_cast<int>(d.rows.size());
    d.rows.push_back(std::move(row));
  }
}

}  // namespace

Decomposition decompose(const Model& model) {
  Decomposition d;
  const std::vector<StrutCopyList> copies = place_and_glue_struts(model, d);
  glue_joints(model, copies, d);
  hold_dirichlet_nodes(model, copies, d);
  d.equality_rows = static_cast<int>(d.rows.size());
  d.total_pieces = static_cast<int>(d.subdomains.size());
  add_contact_rows(model, copies, d);
  return d;
}

}  // namespace fetic::solver
