#include "solver/corners.hpp"

#include <unordered_set>

#include "scenes/null_space.hpp"
#include "scenes/union_find.hpp"
#include "solver/edge_averages.hpp"
#include "solver/rigid_modes.hpp"

namespace fetic::solver {
namespace {

using Copies = std::vector<std::pair<int, int>>;  // (box, box-local node)

// Per strut node, its copies in increasing box order (as decompose() makes them).
std::vector<std::vector<Copies>> node_copies(const Model& model, const Decomposition& boxes) {
  std::vector<std::vector<Copies>> copies(model.struts.size());
  for (size_t s = 0; s < model.struts.size(); ++s)
    copies[s].resize(model.struts[s].node_count());
  for (size_t j = 0; j < boxes.subdomains.size(); ++j) {
    const Subdomain& sub = boxes.subdomains[j];
    const StrutMesh& mesh = model.struts[sub.strut];
    for (int i = sub.box.i0; i <= sub.box.i1; ++i)
      for (int k = sub.box.k0; k <= sub.box.k1; ++k)
        copies[sub.strut][mesh.node(i, k)].emplace_back(static_cast<int>(j), sub.box.local(i, k));
  }
  return copies;
}

bool box_corner(const NodeBox& box, int i, int k) {
  return (i == box.i0 || i == box.i1) && (k == box.k0 || k == box.k1);
}

// Whether an interface node (two or more copies) is a corner (corners.hpp).
bool is_corner(const Model& model, const Decomposition& boxes, const StrutMesh& mesh, int node,
               const Copies& c) {
  if (c.size() < 2) return false;
  if (model.kind != scenes::ModelKind::Plane) return true;
  const int across = mesh.ny + 1;
  const int i = node / across, k = node % across;
  for (const auto& [box, local] : c)
    if (box_corner(boxes.subdomains[box].box, i, k)) return true;
  return false;
}

// The cluster each box may join: one for all (plain FETI-DP), or consecutive boxes of a
// strut in groups of cluster_size.
std::vector<int> box_groups(const Decomposition& boxes, int cluster_size) {
  std::vector<int> group(boxes.subdomains.size(), 0);
  if (cluster_size <= 0) return group;
  int next = 0, strut = -1, in_strut = 0;
  for (size_t j = 0; j < boxes.subdomains.size(); ++j) {
    if (boxes.subdomains[j].strut != strut) {
      strut = boxes.subdomains[j].strut;
      in_strut = 0;
      ++next;
    } else if (in_strut % cluster_size == 0) {
      ++next;
    }
    group[j] = next;
    ++in_strut;
  }
  return group;
}

// Joins the DOFs of a node's copies (components [0, components)) that may share a cluster.
void join_copies(const Copies& c, int dofs_per_node, int components, const Decomposition& boxes,
                 const std::vector<int>& group, scenes::UnionFind& dofs,
                 scenes::UnionFind& clusters) {
  for (size_t a = 0; a < c.size(); ++a)
    for (size_t b = a + 1; b < c.size(); ++b) {
      if (group[c[a].first] != group[c[b].first]) continue;
      clusters.join(c[a].first, c[b].first);
      for (int comp = 0; comp < components; ++comp)
        dofs.join(boxes.subdomains[c[a].first].dof_offset + c[a].second * dofs_per_node + comp,
                  boxes.subdomains[c[b].first].dof_offset + c[b].second * dofs_per_node + comp);
    }
}

// An orthonormal basis of C's kernel: the right singular vectors whose singular values
// are below 1e-10 of the largest. Relative, since C's rows are rigid-mode rows whose
// rotation entries carry the scene's length scale (scenes::null_space's absolute floor
// suits only unit-scaled rows).
// The SVD itself is scenes/null_space.cpp's (one copy of Eigen's BDCSVD in the build).
Eigen::MatrixXd kernel_of(const Eigen::MatrixXd& C) {
  return scenes::null_space_relative(C, 1e-10);
}

// The kernel of a cluster as amplitudes of its parts' rigid-body modes.
Eigen::MatrixXd cluster_kernel(const Model& model, const Subdomain& cluster) {
  const std::vector<SubdomainPart>& parts = cluster.parts;
  const int per_part = model.dofs_per_node() == 1 ? 1 : 3;
  const int n = static_cast<int>(parts.size()) * per_part;
  bool one_strut = true;
  for (const SubdomainPart& part : parts)
    one_strut = one_strut && part.strut == parts.front().strut;
  if (one_strut && per_part == 1) return Eigen::MatrixXd::Ones(n, 1);
  if (one_strut) {
    // The strut's rigid motions about the mean of the box centres, in each box's modes
    // (rotation, ux, uy about its own centre; rigid_modes.cpp).
    const StrutMesh& mesh = model.struts[parts.front().strut];
    std::vector<Vec2> centres;
    Vec2 mean(0, 0);
    for (const SubdomainPart& part : parts)
      mean += centres.emplace_back(box_centre(mesh, part.box));
    mean /= static_cast<double>(parts.size());
    Eigen::MatrixXd N = Eigen::MatrixXd::Zero(n, 3);
    for (size_t p = 0; p < parts.size(); ++p) {
      const Vec2 offset = centres[p] - mean;
      N(3 * p, 0) = 1.0;
      N(3 * p + 1, 0) = -offset.y();
      N(3 * p + 2, 0) = offset.x();
      N(3 * p + 1, 1) = 1.0;
      N(3 * p + 2, 2) = 1.0;
    }
    return N;
  }
  // Boxes of several struts (frame joints): the amplitudes whose motions agree on every
  // shared DOF, the null space of those conditions.
  std::vector<int> first_part(cluster.dof_count, -1), first_local(cluster.dof_count, -1);
  std::vector<Eigen::MatrixXd> modes;
  for (const SubdomainPart& part : parts)
    modes.push_back(rigid_body_modes(model.struts[part.strut], part.box));
  std::vector<Eigen::RowVectorXd> conditions;
  for (size_t p = 0; p < parts.size(); ++p)
    for (size_t l = 0; l < parts[p].dofs.size(); ++l) {
      const int dof = parts[p].dofs[l];
      if (first_part[dof] < 0) {
        first_part[dof] = static_cast<int>(p);
        first_local[dof] = static_cast<int>(l);
        continue;
      }
      Eigen::RowVectorXd row = Eigen::RowVectorXd::Zero(n);
      row.segment(per_part * p, per_part) = modes[p].row(static_cast<int>(l));
      row.segment(per_part * first_part[dof], per_part) -=
          modes[first_part[dof]].row(first_local[dof]);
      conditions.push_back(row);
    }
  Eigen::MatrixXd C = Eigen::MatrixXd::Zero(std::max<size_t>(conditions.size(), 1), n);
  for (size_t r = 0; r < conditions.size(); ++r)
    C.row(static_cast<int>(r)) = conditions[r];
  return kernel_of(C);
}

}  // namespace

std::vector<std::vector<int>> corner_nodes(const Model& model, const Decomposition& boxes) {
  const auto copies = node_copies(model, boxes);
  std::vector<std::vector<int>> corners(model.struts.size());
  for (size_t s = 0; s < model.struts.size(); ++s)
    for (int node = 0; node < model.struts[s].node_count(); ++node)
      if (is_corner(model, boxes, model.struts[s], node, copies[s][node]))
        corners[s].push_back(node);
  for (const JointLink& joint : model.joints)
    for (const auto& [strut, node] : joint.ends)
      corners[strut].push_back(node);
  for (auto& list : corners) {
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
  }
  return corners;
}

namespace {

struct Joined {
  std::vector<int> cluster_of_box;
  std::vector<int> dof_of;  // per box DOF (dof_offset + local): its cluster DOF
};

// Joins the corners and numbers the clusters and their DOFs; fills d.subdomains.
Joined join(const Model& model, const Decomposition& boxes, int cluster_size, Decomposition& d) {
  const int dpn = model.dofs_per_node();
  const std::vector<int> group = box_groups(boxes, cluster_size);
  scenes::UnionFind dofs(boxes.total_dofs), clusters(static_cast<int>(boxes.subdomains.size()));
  const auto copies = node_copies(model, boxes);
  for (size_t s = 0; s < model.struts.size(); ++s)
    for (int node = 0; node < model.struts[s].node_count(); ++node)
      if (is_corner(model, boxes, model.struts[s], node, copies[s][node]))
        join_copies(copies[s][node], dpn, dpn, boxes, group, dofs, clusters);
  for (const JointLink& joint : model.joints) {
    Copies ends;
    for (const auto& [strut, node] : joint.ends)
      ends.push_back(copies[strut][node].front());
    join_copies(ends, dpn, joint.shared, boxes, group, dofs, clusters);
  }

  Joined joined;
  const int box_count = static_cast<int>(boxes.subdomains.size());
  joined.cluster_of_box.assign(box_count, -1);
  std::vector<int> cluster_of_root(box_count, -1);
  for (int j = 0; j < box_count; ++j) {
    int& c = cluster_of_root[clusters.root(j)];
    if (c < 0) {
      c = static_cast<int>(d.subdomains.size());
      d.subdomains.emplace_back();
    }
    joined.cluster_of_box[j] = c;
    d.subdomains[c].parts.push_back({boxes.subdomains[j].strut, boxes.subdomains[j].box, j, {}});
  }
  joined.dof_of.assign(boxes.total_dofs, -1);
  std::vector<int> dof_of_root(boxes.total_dofs, -1);
  for (Subdomain& cluster : d.subdomains) {
    int count = 0;
    for (SubdomainPart& part : cluster.parts) {
      const Subdomain& box = boxes.subdomains[part.piece];
      part.dofs.resize(box.dof_count);
      for (int l = 0; l < box.dof_count; ++l) {
        int& dof = dof_of_root[dofs.root(box.dof_offset + l)];
        if (dof < 0) dof = count++;
        part.dofs[l] = joined.dof_of[box.dof_offset + l] = dof;
      }
    }
    cluster.strut = cluster.parts.front().strut;
    cluster.box = cluster.parts.front().box;
    cluster.dof_count = count;
    cluster.dof_offset = d.total_dofs;
    d.total_dofs += count;
    cluster.load = Eigen::VectorXd::Zero(count);
    for (const SubdomainPart& part : cluster.parts)
      for (int l = 0; l < static_cast<int>(part.dofs.size()); ++l)
        cluster.load(part.dofs[l]) += boxes.subdomains[part.piece].load(l);
  }
  return joined;
}

long long dof_key(const RowEntry& e) {
  return (static_cast<long long>(e.subdomain) << 32) | e.dof;
}

// The cluster DOFs that a gluing row (between distinct cluster DOFs) or a contact row
// touches: a clamped DOF among them stays a Dirichlet row.
std::unordered_set<long long> dofs_in_rows(const Decomposition& boxes, const Joined& joined) {
  auto moved_key = [&](const RowEntry& e) {
    return dof_key({joined.cluster_of_box[e.subdomain],
                    joined.dof_of[boxes.subdomains[e.subdomain].dof_offset + e.dof], 0.0});
  };
  std::unordered_set<long long> touched;
  for (const Row& row : boxes.rows) {
    if (row.kind == RowKind::Dirichlet) continue;
    std::unordered_set<long long> keys;
    for (const auto* list : {&row.entries, &row.copies})
      for (const RowEntry& entry : *list)
        keys.insert(moved_key(entry));
    if (row.kind == RowKind::Contact || keys.size() >= 2) touched.insert(keys.begin(), keys.end());
  }
  return touched;
}

// The rows of the boxes on the clusters: gluing rows per node component over the
// distinct cluster DOFs of its copies (none when all are joined), contact rows with their
// entries moved. A clamped DOF of a cluster of several boxes that no other row touches is
// made primal (Subdomain::fixed): total FETI's Dirichlet rows would leave such a cluster
// only its own rigid-body modes as coarse space, too few to hold the clamp (the condition
// number grew like the square of the boxes along a strut, docs/METHODS.md "FETI-DP").
// Other clamped DOFs keep a Dirichlet row, once per cluster DOF.
void move_rows(const Decomposition& boxes, const Joined& joined, Decomposition& d) {
  auto moved = [&](const RowEntry& e) {
    return RowEntry{joined.cluster_of_box[e.subdomain],
                    joined.dof_of[boxes.subdomains[e.subdomain].dof_offset + e.dof], e.value};
  };
  auto same = [](const RowEntry& a, const RowEntry& b) {
    return a.subdomain == b.subdomain && a.dof == b.dof;
  };
  const std::unordered_set<long long> touched = dofs_in_rows(boxes, joined);
  std::unordered_set<long long> held;
  for (int r = 0; r < boxes.equality_rows;) {
    const Row& row = boxes.rows[r];
    if (row.kind == RowKind::Dirichlet) {
      const RowEntry e = moved(row.entries.front());
      if (held.insert(dof_key(e)).second) {
        Subdomain& cluster = d.subdomains[e.subdomain];
        if (cluster.parts.size() >= 2 && !touched.count(dof_key(e)))
          cluster.fixed.push_back(e.dof);
        else
          d.rows.push_back({RowKind::Dirichlet, -1, 0.0, {e}, {}});
      }
      ++r;
      continue;
    }
    // A run of gluing rows of one node component: the same copies.
    int end = r + 1;
    while (end < boxes.equality_rows && boxes.rows[end].kind == RowKind::Gluing &&
           boxes.rows[end].copies.size() == row.copies.size() &&
           std::equal(row.copies.begin(), row.copies.end(), boxes.rows[end].copies.begin(), same))
      ++end;
    std::vector<RowEntry> distinct;
    for (const RowEntry& copy : row.copies) {
      const RowEntry e = moved(copy);
      bool seen = false;
      for (const RowEntry& other : distinct)
        seen = seen || same(other, e);
      if (!seen) distinct.push_back(e);
    }
    RedundantGroup group;
    group.copies = static_cast<int>(distinct.size());
    for (size_t i = 0; i < distinct.size(); ++i)
      for (size_t j = i + 1; j < distinct.size(); ++j) {
        Row glue;
        glue.entries = {{distinct[i].subdomain, distinct[i].dof, 1.0},
                        {distinct[j].subdomain, distinct[j].dof, -1.0}};
        glue.copies = distinct;
        group.rows.push_back(static_cast<int>(d.rows.size()));
        group.ends.emplace_back(static_cast<int>(i), static_cast<int>(j));
        d.rows.push_back(std::move(glue));
      }
    if (group.copies >= 3) d.redundant_groups.push_back(std::move(group));
    r = end;
  }
  d.equality_rows = d.row_count();
  d.pair_row.assign(boxes.pair_row.size(), -1);
  std::vector<int> new_row(boxes.row_count(), -1);
  for (int r = boxes.equality_rows; r < boxes.row_count(); ++r) {
    Row row = boxes.rows[r];
    std::vector<RowEntry> entries;
    for (const RowEntry& entry : row.entries) {
      const RowEntry e = moved(entry);
      auto found = std::find_if(entries.begin(), entries.end(),
                                [&](const RowEntry& other) { return same(other, e); });
      if (found == entries.end())
        entries.push_back(e);
      else
        found->value += e.value;
    }
    row.entries = std::move(entries);
    new_row[r] = d.row_count();
    d.rows.push_back(std::move(row));
  }
  for (size_t k = 0; k < boxes.pair_row.size(); ++k)
    if (boxes.pair_row[k] >= 0) d.pair_row[k] = new_row[boxes.pair_row[k]];
}

// A cluster's fixed DOFs: no load, and its kernel only the motions that leave them at
// zero (none for a clamped strut; a pinned frame keeps its rotation about the pin).
void hold_fixed(const Model& model, Subdomain& cluster) {
  if (cluster.fixed.empty()) return;
  std::sort(cluster.fixed.begin(), cluster.fixed.end());
  for (int dof : cluster.fixed)
    cluster.load(dof) = 0.0;
  if (cluster.mode_count == 0) return;
  const Eigen::MatrixXd R = subdomain_modes(model, cluster);
  Eigen::MatrixXd C(cluster.fixed.size(), cluster.mode_count);
  for (size_t f = 0; f < cluster.fixed.size(); ++f)
    C.row(static_cast<int>(f)) = R.row(cluster.fixed[f]);
  cluster.part_modes = cluster.part_modes * kernel_of(C);
  cluster.mode_count = static_cast<int>(cluster.part_modes.cols());
}

}  // namespace

Decomposition join_corners(const Model& model, const Decomposition& boxes, int cluster_size,
                           bool edge_averages) {
  Decomposition d;
  const Joined joined = join(model, boxes, cluster_size, d);
  move_rows(boxes, joined, d);
  if (edge_averages) tie_edge_averages(model, d);
  d.total_pieces = boxes.total_pieces;
  for (Subdomain& cluster : d.subdomains) {
    cluster.part_modes = cluster_kernel(model, cluster);
    cluster.mode_count = static_cast<int>(cluster.part_modes.cols());
    hold_fixed(model, cluster);
    cluster.mode_offset = d.total_modes;
    d.total_modes += cluster.mode_count;
  }
  return d;
}

namespace {

// Adds K(a, b) = v, a tied DOF's couplings moved onto its terms (T'KT, edge_averages.hpp);
// the tied DOF keeps its own diagonal, so that K stays regular there.
void add_entry(const Subdomain& sub, const std::vector<int>& tie_of, int a, int b, double v,
               std::vector<Eigen::Triplet<double>>& entries) {
  if (tie_of[a] < 0 && tie_of[b] < 0) {
    entries.emplace_back(a, b, v);
    return;
  }
  if (a == b) entries.emplace_back(a, a, v);
  const std::vector<std::pair<int, double>> self_a{{a, 1.0}}, self_b{{b, 1.0}};
  const auto& terms_a = tie_of[a] < 0 ? self_a : sub.ties[tie_of[a]].terms;
  const auto& terms_b = tie_of[b] < 0 ? self_b : sub.ties[tie_of[b]].terms;
  for (const auto& [i, ci] : terms_a)
    for (const auto& [k, ck] : terms_b)
      entries.emplace_back(i, k, v * ci * ck);
}

}  // namespace

SparseMatrix subdomain_stiffness(const Model& model, const Subdomain& sub) {
  if (sub.parts.empty()) return assemble_stiffness(model.struts[sub.strut], sub.box);
  std::vector<char> fixed(sub.dof_count, 0);
  for (int dof : sub.fixed)
    fixed[dof] = 1;
  std::vector<int> tie_of(sub.dof_count, -1);
  for (size_t t = 0; t < sub.ties.size(); ++t)
    tie_of[sub.ties[t].dof] = static_cast<int>(t);
  std::vector<Eigen::Triplet<double>> entries;
  for (const SubdomainPart& part : sub.parts) {
    const SparseMatrix K = assemble_stiffness(model.struts[part.strut], part.box);
    for (int col = 0; col < K.outerSize(); ++col)
      for (SparseMatrix::InnerIterator it(K, col); it; ++it) {
        const int a = part.dofs[it.row()], b = part.dofs[col];
        if (a == b || !(fixed[a] || fixed[b])) add_entry(sub, tie_of, a, b, it.value(), entries);
      }
  }
  SparseMatrix K(sub.dof_count, sub.dof_count);
  K.setFromTriplets(entries.begin(), entries.end());
  return K;
}

Eigen::MatrixXd subdomain_modes(const Model& model, const Subdomain& sub) {
  if (sub.parts.empty()) return rigid_body_modes(model.struts[sub.strut], sub.box);
  Eigen::MatrixXd R = Eigen::MatrixXd::Zero(sub.dof_count, sub.mode_count);
  const int per_part = static_cast<int>(sub.part_modes.rows() / sub.parts.size());
  for (size_t p = 0; p < sub.parts.size(); ++p) {
    const SubdomainPart& part = sub.parts[p];
    const Eigen::MatrixXd motion = rigid_body_modes(model.struts[part.strut], part.box) *
                                   sub.part_modes.middleRows(per_part * p, per_part);
    for (size_t l = 0; l < part.dofs.size(); ++l)
      R.row(part.dofs[l]) = motion.row(static_cast<int>(l));
  }
  for (const Subdomain::SumDof& sum : sub.sums)
    for (const auto& [dof, coefficient] : sum.of)
      R.row(sum.dof) += coefficient * R.row(dof);
  for (const Subdomain::TiedDof& tie : sub.ties)  // held in K: no motion there
    R.row(tie.dof).setZero();
  return R;
}

}  // namespace fetic::solver
