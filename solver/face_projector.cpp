#include "solver/face_projector.hpp"

namespace fetic::solver {

FaceProjector::FaceProjector(const FetiSystem& system, const CoarseProblem& equality)
    : system_(system), equality_(equality) {
  const SparseMatrix& G = system.G();
  const DualSpace& space = system.space();
  const int modes = static_cast<int>(G.rows());
  position_.assign(modes, -1);
  for (int k = 0; k < space.rows(); ++k) {
    if (!space.is_contact(k)) continue;
    for (SparseMatrix::InnerIterator it(G, k); it; ++it)
      if (position_[it.row()] < 0) {
        position_[it.row()] = static_cast<int>(contact_modes_.size());
        contact_modes_.push_back(static_cast<int>(it.row()));
      }
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
  if (face == face_ && S_.size() > 0) return;
  face_ = face;
  const int c = static_cast<int>(contact_modes_.size());
  S_ = Eigen::MatrixXd::Zero(c, c);
  const SparseMatrix& G = system_.G();
  const DualSpace& space = system_.space();
  for (int k = 0; k < space.rows(); ++k) {
    if (!space.is_contact(k) || !face_[k]) continue;
    for (SparseMatrix::InnerIterator a(G, k); a; ++a)
      for (SparseMatrix::InnerIterator b(G, k); b; ++b)
        S_(position_[a.row()], position_[b.row()]) += a.value() * b.value();
  }
  correction_.compute(Eigen::MatrixXd::Identity(c, c) + S_ * UXU_);
}

void FaceProjector::project(Eigen::VectorXd& v) const {
  const SparseMatrix& G = system_.G();
  const Eigen::VectorXd b = G * v;
  Eigen::VectorXd y = equality_.solve(b);
  if (XU_.cols() > 0) y -= XU_ * correction_.solve(S_ * (XU_.transpose() * b));
  const Eigen::VectorXd back = G.transpose() * y;
  for (int k = 0; k < system_.space().rows(); ++k)
    if (face_[k]) v(k) -= back(k);
}

}  // namespace fetic::solver
