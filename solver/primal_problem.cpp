#include "solver/primal_problem.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include "scenes/message_text.hpp"
#include "solver/rigid_modes.hpp"
#include "solver/threads.hpp"

namespace fetic::solver {
namespace {

// Below this CHOLMOD's diagonal-ratio estimate the factor is numerically singular.
constexpr double kSingularRcond = 1e-15;

}  // namespace

std::string singular_message(const Model& model, int strut, CholmodFactor::Result result,
                             const std::string& part) {
  const std::string name = "strut '" + model.strut_names[strut] + "'";
  switch (result) {
    case CholmodFactor::Result::OutOfMemory:
      return name + ": out of memory while factorizing the stiffness of " + part;
    case CholmodFactor::Result::Failed:
      return name + ": CHOLMOD failed to factorize the stiffness of " + part;
    default:
      break;
  }
  const std::string singular =
      name + ": the stiffness of " + part + " is singular beyond its rigid-body modes";
  const StrutMesh& mesh = model.struts[static_cast<size_t>(strut)];
  if (mesh.dofs_per_node != 3)
    return singular + " (check E, " + (mesh.ny > 0 ? "thickness" : "area") +
           " and the mesh proportions)";
  // A beam element's bending stiffness 12 E I / h^3 against its axial one E A / h: when
  // the inertia is what makes it vanish, say so.
  const double h = mesh.length / std::max(mesh.nx, 1);
  const double bending_over_axial = 12.0 * mesh.inertia / (mesh.area * h * h);
  if (!(bending_over_axial > 1e-10))
    return singular + ": its bending stiffness is " + scenes::number_text(bending_over_axial) +
           " times its axial stiffness (inertia " + scenes::number_text(mesh.inertia) + ", area " +
           scenes::number_text(mesh.area) + ", element length " + scenes::number_text(h) +
           "); check inertia";
  return singular + " (check E, area, inertia and the mesh proportions)";
}

namespace {

// Struts that share DOFs: a group joined by joints (frame model), else each strut alone.
std::vector<std::vector<int>> strut_groups(const Model& model) {
  if (model.frame()) return model.kinematics.groups;
  std::vector<std::vector<int>> groups;
  for (int s = 0; s < static_cast<int>(model.struts.size()); ++s)
    groups.push_back({s});
  return groups;
}

// Frame model: per (strut, node) at a joint, the end that owns the joint's shared DOFs
// (the smallest strut, numbered first) and how many components they share.
struct JointOwner {
  int strut = -1, node = -1, shared = 0;
};
std::vector<std::map<int, JointOwner>> joint_owners(const Model& model) {
  std::vector<std::map<int, JointOwner>> owners(model.struts.size());
  for (const JointLink& joint : model.joints) {
    const auto first = *std::min_element(joint.ends.begin(), joint.ends.end());
    for (const auto& [strut, node] : joint.ends)
      owners[strut][node] = {first.first, first.second, joint.shared};
  }
  return owners;
}

}  // namespace

PrimalProblem::PrimalProblem(const Model& model, bool factorize_blocks) : model_(model) {
  number_free_dofs();
  assemble_blocks(factorize_blocks);
  build_contact_rows();
}

void PrimalProblem::number_free_dofs() {
  const Model& model = model_;
  const int strut_count = static_cast<int>(model.struts.size());
  const std::vector<std::vector<int>> groups = strut_groups(model);
  const auto owners = joint_owners(model);
  // Free DOFs, numbered group by group, strut by strut, node by node.
  global_of_.resize(strut_count);
  for (const std::vector<int>& group : groups) {
    StrutBlock block;
    block.strut = group.front();
    block.struts = group;
    block.offset = size_;
    int next = size_;
    for (int s : group) {
      const StrutMesh& mesh = model.struts[s];
      const int d = mesh.dofs_per_node;
      global_of_[s].assign(mesh.dof_count(), -1);
      auto held = model.held_nodes[s].begin();
      for (int node = 0; node < mesh.node_count(); ++node) {
        unsigned mask = 0;
        if (held != model.held_nodes[s].end() && held->node == node) mask = (held++)->components;
        const auto owner = owners[s].find(node);
        for (int c = 0; c < d; ++c) {
          if (mask >> c & 1u) continue;
          if (owner != owners[s].end() && c < owner->second.shared &&
              !(owner->second.strut == s && owner->second.node == node)) {
            global_of_[s][node * d + c] =
                global_of_[owner->second.strut][owner->second.node * d + c];
            continue;
          }
          global_of_[s][node * d + c] = next++;
        }
      }
    }
    block.size = next - size_;
    size_ = next;
    blocks_.push_back(std::move(block));
  }
}

void PrimalProblem::assemble_blocks(bool factorize_blocks) {
  const Model& model = model_;
  std::vector<std::vector<int>> motions_of_group(blocks_.size());
  for (size_t m = 0; m < model.kinematics.motions.size(); ++m)
    motions_of_group[model.kinematics.motions[m].group].push_back(static_cast<int>(m));
  std::vector<Eigen::Triplet<double>> k_entries, r_entries;
  f_ = Eigen::VectorXd::Zero(size_);
  for (size_t g = 0; g < blocks_.size(); ++g) {
    StrutBlock& block = blocks_[g];
    std::vector<Eigen::Triplet<double>> entries;
    for (int s : block.struts) {
      const SparseMatrix full = assemble_stiffness(model.struts[s], whole_strut(model.struts[s]));
      const std::vector<int>& global = global_of_[s];
      for (int col = 0; col < full.outerSize(); ++col)
        for (SparseMatrix::InnerIterator it(full, col); it; ++it)
          if (global[it.row()] >= 0 && global[col] >= 0) {
            entries.emplace_back(global[it.row()] - block.offset, global[col] - block.offset,
                                 it.value());
            k_entries.emplace_back(global[it.row()], global[col], it.value());
          }
    }
    SparseMatrix Ks(block.size, block.size);
    Ks.setFromTriplets(entries.begin(), entries.end());
    if (model.frame()) {
      block.kernel = frame_kernel(motions_of_group[g], block);
    } else if (model.floating(block.strut)) {
      // No DOF is held, so block DOFs are strut DOFs.
      block.kernel =
          rigid_body_modes(model.struts[block.strut], whole_strut(model.struts[block.strut]));
      kernel_struts_.resize(kernel_struts_.size() + block.kernel.cols(), {block.strut});
    } else {
      block.kernel.resize(block.size, 0);
    }
    const int first_column =
        static_cast<int>(kernel_struts_.size()) - static_cast<int>(block.kernel.cols());
    for (int m = 0; m < block.kernel.cols(); ++m)
      for (int j = 0; j < block.size; ++j)
        if (block.kernel(j, m) != 0.0)
          r_entries.emplace_back(block.offset + j, first_column + m, block.kernel(j, m));
    if (factorize_blocks) {
      const CholmodFactor::Result result = block.inverse.factorize(Ks, block.kernel);
      if (result != CholmodFactor::Result::Ok || block.inverse.rcond() < kSingularRcond)
        throw SolverError(
            singular_message(model, block.strut, result,
                             block.struts.size() > 1 ? "its group of joined struts" : "the strut"));
    }
    for (int s : block.struts)
      for (int dof = 0; dof < model.struts[s].dof_count(); ++dof)
        if (global_of_[s][dof] >= 0) f_(global_of_[s][dof]) += model.loads[s](dof);
  }
  K_.resize(size_, size_);
  K_.setFromTriplets(k_entries.begin(), k_entries.end());
  R_.resize(size_, static_cast<int>(kernel_struts_.size()));
  R_.setFromTriplets(r_entries.begin(), r_entries.end());
}

// Contact rows: (u_a - u_b) . n <= gap, on the free DOFs of both nodes.
void PrimalProblem::build_contact_rows() {
  const Model& model = model_;
  const int m = static_cast<int>(model.pairs.size());
  std::vector<Eigen::Triplet<double>> a_entries;
  c_.resize(m);
  for (int k = 0; k < m; ++k) {
    const ContactPair& pair = model.pairs[k];
    c_(k) = pair.gap;
    for (const ContactSide& side : contact_sides(model, pair)) {
      const StrutMesh& mesh = model.struts[side.strut];
      for (int c = 0; c < mesh.dofs_per_node; ++c) {
        const int global = global_of_[side.strut][side.node * mesh.dofs_per_node + c];
        if (global >= 0 && side.coefficients(c) != 0.0)
          a_entries.emplace_back(k, global, side.coefficients(c));
      }
    }
  }
  A_.resize(m, size_);
  A_.setFromTriplets(a_entries.begin(), a_entries.end());
}

void PrimalProblem::apply_pseudo_inverse(const Eigen::VectorXd& x, Eigen::VectorXd& y) const {
  y.resize(size_);
  const int count = static_cast<int>(blocks_.size());
#pragma omp parallel for schedule(dynamic) num_threads(threads_for(size_))
  for (int b = 0; b < count; ++b) {
    const StrutBlock& block = blocks_[b];
    block.inverse.apply(x.data() + block.offset, y.data() + block.offset);
  }
}

std::vector<Piece> PrimalProblem::pieces(const Eigen::VectorXd& u) const {
  std::vector<Piece> result;
  for (const StrutBlock& block : blocks_) {
    for (int s : block.struts) {
      const StrutMesh& mesh = model_.struts[s];
      Eigen::VectorXd dofs = Eigen::VectorXd::Zero(mesh.dof_count());
      for (int dof = 0; dof < mesh.dof_count(); ++dof)
        if (global_of_[s][dof] >= 0) dofs(dof) = u(global_of_[s][dof]);
      Piece piece;
      piece.strut = s;
      piece.box = whole_strut(mesh);
      for (int node = 0; node < mesh.node_count(); ++node)
        add_node_state(mesh, dofs.data() + node * mesh.dofs_per_node, piece);
      result.push_back(std::move(piece));
    }
  }
  return result;
}

Eigen::MatrixXd PrimalProblem::frame_kernel(const std::vector<int>& motions,
                                            const StrutBlock& block) {
  const scenes::FrameKinematics& kinematics = model_.kinematics;
  Eigen::MatrixXd kernel = Eigen::MatrixXd::Zero(block.size, static_cast<int>(motions.size()));
  for (size_t m = 0; m < motions.size(); ++m) {
    const scenes::FreeMotion& motion = kinematics.motions[motions[m]];
    std::vector<int> moved;
    for (int s : block.struts) {
      const StrutMesh& mesh = model_.struts[s];
      double largest = 0.0;
      for (int node = 0; node < mesh.node_count(); ++node) {
        const auto u =
            scenes::motion_at(kinematics, motion, s, {mesh.nodes[node].x(), mesh.nodes[node].y()});
        for (int c = 0; c < 3; ++c) {
          const int global = global_of_[s][3 * node + c];
          if (global >= 0) kernel(global - block.offset, static_cast<int>(m)) = u[c];
        }
        largest = std::max(largest, std::hypot(u[0], u[1]));
      }
      if (largest > 1e-9) moved.push_back(s);
    }
    kernel_struts_.push_back(moved);
  }
  return kernel;
}

}  // namespace fetic::solver
