#include "solver/edge_averages.hpp"

#include <map>
#include <tuple>
#include <unordered_set>

namespace fetic::solver {
namespace {

// One gluing row of an edge: its index and its DOFs in the first and the second box.
struct EdgeRow {
  int row = 0;
  int dof_p = 0;
  int dof_q = 0;
};

// (cluster, first box, second box, component): one edge and component.
using EdgeKey = std::tuple<int, int, int, int>;

long long edge_dof_key(const RowEntry& e) {
  return (static_cast<long long>(e.subdomain) << 32) | e.dof;
}

// Per cluster DOF, the part that holds it alone (-1: none, -2: several, a corner) and
// its box-local DOF there.
struct Owners {
  std::vector<int> part, local;
};

Owners owners(const Subdomain& cluster) {
  Owners o{std::vector<int>(cluster.dof_count, -1), std::vector<int>(cluster.dof_count, -1)};
  for (size_t p = 0; p < cluster.parts.size(); ++p) {
    const std::vector<int>& dofs = cluster.parts[p].dofs;
    for (size_t l = 0; l < dofs.size(); ++l) {
      o.part[dofs[l]] = o.part[dofs[l]] == -1 ? static_cast<int>(p) : -2;
      o.local[dofs[l]] = static_cast<int>(l);
    }
  }
  return o;
}

// The gluing rows between two boxes of one cluster, by edge and component, in row order.
std::map<EdgeKey, std::vector<EdgeRow>> edge_rows(const Model& model, const Decomposition& d) {
  std::unordered_set<long long> held;  // DOFs of Dirichlet and contact rows
  for (const Row& row : d.rows)
    if (row.kind != RowKind::Gluing)
      for (const RowEntry& e : row.entries)
        held.insert(edge_dof_key(e));
  std::vector<Owners> owner(d.subdomains.size());
  for (size_t j = 0; j < d.subdomains.size(); ++j)
    if (d.subdomains[j].parts.size() >= 2) owner[j] = owners(d.subdomains[j]);
  std::map<EdgeKey, std::vector<EdgeRow>> found;
  std::vector<EdgeKey> spoiled;
  for (int r = 0; r < d.equality_rows; ++r) {
    const Row& row = d.rows[r];
    if (row.kind != RowKind::Gluing || row.entries.size() != 2 || row.copies.size() != 2) continue;
    const RowEntry &a = row.entries[0], &b = row.entries[1];
    if (a.subdomain != b.subdomain || owner[a.subdomain].part.empty()) continue;
    const Owners& o = owner[a.subdomain];
    const int pa = o.part[a.dof], pb = o.part[b.dof];
    if (pa < 0 || pb < 0 || pa == pb) continue;
    const EdgeKey key{a.subdomain, std::min(pa, pb), std::max(pa, pb),
                      o.local[a.dof] % model.dofs_per_node()};
    if (held.count(edge_dof_key(a)) || held.count(edge_dof_key(b))) spoiled.push_back(key);
    found[key].push_back(pa < pb ? EdgeRow{r, a.dof, b.dof} : EdgeRow{r, b.dof, a.dof});
  }
  for (const EdgeKey& key : spoiled)
    found.erase(key);
  return found;
}

// Removes the rows marked in `drop`, renumbering the contact pairs' and the redundant
// groups' rows.
void drop_rows(Decomposition& d, const std::vector<char>& drop) {
  std::vector<int> index(d.rows.size(), -1);
  std::vector<Row> kept;
  int equality = 0;
  for (size_t r = 0; r < d.rows.size(); ++r) {
    if (drop[r]) continue;
    index[r] = static_cast<int>(kept.size());
    if (static_cast<int>(r) < d.equality_rows) ++equality;
    kept.push_back(std::move(d.rows[r]));
  }
  d.rows = std::move(kept);
  d.equality_rows = equality;
  for (int& r : d.pair_row)
    if (r >= 0) r = index[r];
  for (RedundantGroup& group : d.redundant_groups)
    for (int& r : group.rows)
      r = index[r];
}

// One edge and component: the sum s of the first box's copies becomes a DOF of its own,
// shared by both boxes, and each box's copy of the edge's last node is tied to it,
// u_m = s - sum_{i != m} u_i; the gluing row of that node is dropped.
void tie_edge(const std::vector<EdgeRow>& rows, Subdomain& cluster, std::vector<char>& drop) {
  const EdgeRow& last = rows.back();
  const int s = cluster.dof_count++;
  cluster.load.conservativeResize(cluster.dof_count);
  cluster.load(s) = 0.0;
  Subdomain::TiedDof tp{last.dof_p, {{s, 1.0}}}, tq{last.dof_q, {{s, 1.0}}};
  Subdomain::SumDof sum{s, {}};
  for (const EdgeRow& r : rows) {
    sum.of.emplace_back(r.dof_p, 1.0);
    if (r.row == last.row) continue;
    tp.terms.emplace_back(r.dof_p, -1.0);
    tq.terms.emplace_back(r.dof_q, -1.0);
  }
  for (Subdomain::TiedDof* tie : {&tp, &tq}) {  // T'f: the tied DOF's load onto its terms
    for (const auto& [dof, coefficient] : tie->terms)
      cluster.load(dof) += coefficient * cluster.load(tie->dof);
    cluster.load(tie->dof) = 0.0;
    cluster.ties.push_back(std::move(*tie));
  }
  cluster.sums.push_back(std::move(sum));
  drop[last.row] = 1;
}

}  // namespace

void tie_edge_averages(const Model& model, Decomposition& d) {
  if (model.kind != scenes::ModelKind::Plane) return;
  std::vector<char> drop(d.rows.size(), 0);
  for (const auto& [key, rows] : edge_rows(model, d))
    tie_edge(rows, d.subdomains[std::get<0>(key)], drop);
  drop_rows(d, drop);
  d.total_dofs = 0;  // the clusters grew by their edges' sums
  for (Subdomain& sub : d.subdomains) {
    sub.dof_offset = d.total_dofs;
    d.total_dofs += sub.dof_count;
  }
}

}  // namespace fetic::solver
