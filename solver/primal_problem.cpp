#include "solver/primal_problem.hpp"

#include <algorithm>

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
      return name + ": the stiffness of " + part +
             " is singular beyond its rigid-body modes (check E, area/thickness and the mesh "
             "proportions)";
  }
}

PrimalProblem::PrimalProblem(const Model& model, bool factorize_blocks) : model_(model) {
  const int strut_count = static_cast<int>(model.struts.size());
  // Free DOFs per strut, numbered strut by strut.
  std::vector<std::vector<int>> global_of(strut_count);
  for (int s = 0; s < strut_count; ++s) {
    const StrutMesh& mesh = model.struts[s];
    StrutBlock block;
    block.strut = s;
    block.offset = size_;
    std::vector<char> clamped(mesh.node_count(), 0);
    for (int node : model.clamped_nodes[s])
      clamped[node] = 1;
    global_of[s].assign(mesh.dof_count(), -1);
    for (int node = 0; node < mesh.node_count(); ++node) {
      if (clamped[node]) continue;
      for (int c = 0; c < mesh.dofs_per_node; ++c) {
        const int dof = node * mesh.dofs_per_node + c;
        global_of[s][dof] = size_ + static_cast<int>(block.strut_dofs.size());
        block.strut_dofs.push_back(dof);
      }
    }
    block.size = static_cast<int>(block.strut_dofs.size());
    size_ += block.size;
    blocks_.push_back(std::move(block));
  }

  std::vector<Eigen::Triplet<double>> k_entries, r_entries;
  f_ = Eigen::VectorXd::Zero(size_);
  for (StrutBlock& block : blocks_) {
    const StrutMesh& mesh = model.struts[block.strut];
    const SparseMatrix full = assemble_stiffness(mesh, whole_strut(mesh));
    std::vector<int> local(mesh.dof_count(), -1);
    for (int j = 0; j < block.size; ++j)
      local[block.strut_dofs[j]] = j;
    std::vector<Eigen::Triplet<double>> entries;
    for (int col = 0; col < full.outerSize(); ++col)
      for (SparseMatrix::InnerIterator it(full, col); it; ++it)
        if (local[it.row()] >= 0 && local[col] >= 0) {
          entries.emplace_back(local[it.row()], local[col], it.value());
          k_entries.emplace_back(block.offset + local[it.row()], block.offset + local[col],
                                 it.value());
        }
    SparseMatrix Ks(block.size, block.size);
    Ks.setFromTriplets(entries.begin(), entries.end());
    if (model.floating(block.strut)) {
      const Eigen::MatrixXd modes = rigid_body_modes(mesh, whole_strut(mesh));
      block.kernel = modes;  // no DOF is clamped, so block DOFs are strut DOFs
      for (int m = 0; m < modes.cols(); ++m) {
        const int column = static_cast<int>(kernel_struts_.size());
        kernel_struts_.push_back(block.strut);
        for (int j = 0; j < block.size; ++j)
          if (modes(j, m) != 0.0) r_entries.emplace_back(block.offset + j, column, modes(j, m));
      }
    } else {
      block.kernel.resize(block.size, 0);
    }
    if (factorize_blocks) {
      const CholmodFactor::Result result = block.inverse.factorize(Ks, block.kernel);
      if (result != CholmodFactor::Result::Ok || block.inverse.rcond() < kSingularRcond)
        throw SolverError(singular_message(model, block.strut, result, "the strut"));
    }
    for (int j = 0; j < block.size; ++j)
      f_(block.offset + j) = model.loads[block.strut](block.strut_dofs[j]);
  }
  K_.resize(size_, size_);
  K_.setFromTriplets(k_entries.begin(), k_entries.end());
  R_.resize(size_, static_cast<int>(kernel_struts_.size()));
  R_.setFromTriplets(r_entries.begin(), r_entries.end());

  // Contact rows: (u_a - u_b) . n <= gap, on the free DOFs of both nodes.
  const int m = static_cast<int>(model.pairs.size());
  std::vector<Eigen::Triplet<double>> a_entries;
  c_.resize(m);
  for (int k = 0; k < m; ++k) {
    const ContactPair& pair = model.pairs[k];
    c_(k) = pair.gap;
    for (int side = 0; side < 2; ++side) {
      const int s = side == 0 ? pair.strut_a : pair.strut_b;
      const int node = side == 0 ? pair.node_a : pair.node_b;
      const StrutMesh& mesh = model.struts[s];
      const Eigen::VectorXd coefficients =
          component_coefficients(mesh, side == 0 ? pair.normal : Vec2(-pair.normal));
      for (int c = 0; c < mesh.dofs_per_node; ++c) {
        const int global = global_of[s][node * mesh.dofs_per_node + c];
        if (global >= 0 && coefficients(c) != 0.0)
          a_entries.emplace_back(k, global, coefficients(c));
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
    const StrutMesh& mesh = model_.struts[block.strut];
    Eigen::VectorXd dofs = Eigen::VectorXd::Zero(mesh.dof_count());
    for (int j = 0; j < block.size; ++j)
      dofs(block.strut_dofs[j]) = u(block.offset + j);
    Piece piece;
    piece.strut = block.strut;
    piece.box = whole_strut(mesh);
    for (int node = 0; node < mesh.node_count(); ++node)
      piece.displacement.push_back(
          node_displacement(mesh, dofs.data() + node * mesh.dofs_per_node));
    result.push_back(std::move(piece));
  }
  return result;
}

}  // namespace fetic::solver
