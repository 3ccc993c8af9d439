#pragma once
// FETI-DP's coarse space of the contact faces (docs/METHODS.md, "FETI-DP", "Contact
// faces"). In plain FETI-DP a clamped strut is one cluster with no rigid-body modes, so a
// contact row between two such clusters has no coarse space behind it: pressing the end
// face of a strut is resisted by the whole strut (F sees its compliance, growing with
// its length) while the Dirichlet preconditioner sees only the boxes at the face, and
// lambda_max of the preconditioned operator grows with the boxes along a strut. FETI-1
// escapes it because every box's rigid modes are in G. Here the same modes come back as a
// balancing coarse space of the contact rows: per contact and per pair of boxes the
// face's rows cross (one segment of the face), a uniform and a linear column (the normal
// translation and the rotation of that box, seen by the contact rows), U. With W = A U
// and E = U'A U (A MPRGP's operator; at set-up the columns whose supports cannot meet
// share one application of A, and E is block diagonal over the columns sharing a
// cluster: contact_batches.hpp), MPRGP's preconditioner in the face of the free rows
// R becomes Mandel's balancing form
//
//   z = R [ (I - U E^-1 W') M^-1 R (I - W E^-1 U') + U E^-1 U' ] g,
//
// symmetric and positive definite on the face (M^-1 the preconditioner in face as
// before). On span U it is A^-1 exactly, so the long-range modes of the contact faces
// leave the spectrum. Distributed: the columns are numbered from the replicated
// decomposition, every scalar product is an exact sum (the same bits on any number of
// processes), E is formed and inverted alike on every process.

#include <functional>
#include <vector>

#include <Eigen/Core>

#include "solver/contact_batches.hpp"
#include "solver/feti_system.hpp"

namespace fetic::solver {

class ContactCoarseSpace {
 public:
  // out = A x (collective).
  using Operator = std::function<void(const Eigen::VectorXd&, Eigen::VectorXd&)>;
  // z from g on the face `free` (collective).
  using FacePreconditioner =
      std::function<void(const Eigen::VectorXd&, const std::vector<char>&, Eigen::VectorXd&)>;

  ContactCoarseSpace() = default;
  // The columns of `system`'s contact rows and W = A U (collective: applications() of A);
  // with `clamped_only` only the segments between clusters without rigid-body modes
  // (hybrid FETI-DP: a floating cluster's modes are in G already).
  ContactCoarseSpace(const FetiSystem& system, const Operator& apply_A, bool clamped_only = false);

  int columns() const { return static_cast<int>(U_.size()); }
  // Applications of A the set-up took (one per batch of columns, contact_batches.hpp).
  int applications() const { return applications_; }
  // z for the free gradient g (zero off the face) with `inner` as M^-1 (collective).
  void apply(const Eigen::VectorXd& g, const std::vector<char>& free,
             const FacePreconditioner& inner, Eigen::VectorXd& z) const;

 private:
  struct Column {
    std::vector<int> rows;  // local rows
    std::vector<double> values;
  };
  // C'v for every column, exactly summed over the owned rows of all processes.
  Eigen::VectorXd dots(const std::vector<Column>& C, const Eigen::VectorXd& v) const;
  // v += C c.
  static void add(const std::vector<Column>& C, const Eigen::VectorXd& c, Eigen::VectorXd& v);

  // One diagonal block of E: its columns (increasing) and its pseudo-inverse.
  struct Block {
    std::vector<int> columns;
    Eigen::MatrixXd inverse;
  };
  void form_W(const Decomposition& d, const ContactBatches& plan, const Operator& apply_A);
  void form_E_inverse(const std::vector<std::vector<int>>& components);
  void invert_blocks(const std::vector<std::vector<int>>& components,
                     std::vector<Eigen::MatrixXd>& E);
  // E^+ y, block by block.
  Eigen::VectorXd solve_E(const Eigen::VectorXd& y) const;

  const DualSpace* space_ = nullptr;
  std::vector<Column> U_, W_;
  std::vector<Block> blocks_;
  int applications_ = 0;
};

}  // namespace fetic::solver
