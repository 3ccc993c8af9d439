#include "solver/face_projector.hpp"

#include <algorithm>

namespace fetic::solver {

FaceProjector::FaceProjector(const FetiSystem& system, const CoarseProblem& equality)
    : system_(system), equality_(equality) {
  const SparseMatrix& G = system.G();
  const DualSpace& space = system.space();
  // The columns of G of every contact row, replicated in global row order: each process
  // sends those of its owned rows as (row, count, (mode, value) x count).
  std::vector<double> mine;
  for (int k = space.first_contact(); k < space.rows(); ++k) {
    if (!space.owned(k)) continue;
    mine.push_back(space.global_row(k));
    const std::size_t count_at = mine.size();
    mine.push_back(0.0);
    for (SparseMatrix::InnerIterator it(G, k); it; ++it) {
      mine.push_back(static_cast<double>(it.row()));
      mine.push_back(it.value());
      mine[count_at] += 1.0;
    }
  }
  const std::vector<double> all = space.communicator().all_gather(mine);
  for (std::size_t at = 0; at < all.size();) {
    Column column;
    column.row = static_cast<int>(all[at]);
    const int count = static_cast<int>(all[at + 1]);
    at += 2;
    for (int i = 0; i < count; ++i, at += 2)
      column.entries.emplace_back(static_cast<int>(all[at]), all[at + 1]);
    columns_.push_back(std::move(column));
  }
  std::sort(columns_.begin(), columns_.end(),
            [](const Column& a, const Column& b) { return a.row < b.row; });
  column_of_row_.assign(space.global_rows(), -1);
  for (std::size_t i = 0; i < columns_.size(); ++i)
    column_of_row_[columns_[i].row] = static_cast<int>(i);

  const int modes = static_cast<int>(G.rows());
  position_.assign(modes, -1);
  for (const Column& column : columns_)
    for (const auto& [mode, value] : column.entries)
      if (position_[mode] < 0) {
        position_[mode] = static_cast<int>(contact_modes_.size());
        contact_modes_.push_back(mode);
      }
  const int c = static_cast<int>(contact_modes_.size());
  XU_.resize(modes, c);
  Eigen::VectorXd unit = Eigen::VectorXd::Zero(modes);
  for (int i = 0; i < c; ++i) {
    unit(contact_modes_[i]) = 1.0;
    XU_.col(i) = equality.solve(unit);
    unit(contact_modes_[i]) = 0.0;
  }
  UXU_.resize(c, c);
  for (int i = 0; i < c; ++i)
    UXU_.row(i) = XU_.row(contact_modes_[i]);
}

void FaceProjector::set_face(const std::vector<char>& face) {
  const DualSpace& space = system_.space();
  if (!space.any(!has_face_ || face != face_)) return;
  has_face_ = true;
  face_ = face;
  // The free contact rows of every process, in global order: S sums their columns in the
  // same order for any number of processes.
  std::vector<int> mine;
  for (int k = space.first_contact(); k < space.rows(); ++k)
    if (face_[k] && space.owned(k)) mine.push_back(space.global_row(k));
  std::vector<int> free_rows = space.communicator().all_gather(mine);
  std::sort(free_rows.begin(), free_rows.end());
  const int c = static_cast<int>(contact_modes_.size());
  S_ = Eigen::MatrixXd::Zero(c, c);
  for (int row : free_rows) {
    const Column& column = columns_[static_cast<std::size_t>(column_of_row_[row])];
    for (const auto& [a, va] : column.entries)
      for (const auto& [b, vb] : column.entries)
        S_(position_[a], position_[b]) += va * vb;
  }
  correction_.compute(Eigen::MatrixXd::Identity(c, c) + S_ * UXU_);
}

void FaceProjector::project(Eigen::VectorXd& v) const {
  const Eigen::VectorXd b = system_.apply_G(v);  // replicated; v vanishes off the face
  Eigen::VectorXd y = equality_.solve(b);
  if (XU_.cols() > 0) y -= XU_ * correction_.solve(S_ * (XU_.transpose() * b));
  const Eigen::VectorXd back = system_.G().transpose() * y;
  for (int k = 0; k < system_.space().rows(); ++k)
    if (face_[k]) v(k) -= back(k);
}

}  // namespace fetic::solver
