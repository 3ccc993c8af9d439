#include "bench/ipopt_qp.hpp"

#include <IpIpoptApplication.hpp>
#include <IpSolveStatistics.hpp>
#include <IpTNLP.hpp>

#include <chrono>
#include <limits>

#include "solver/primal_problem.hpp"

namespace fetic::bench {
namespace {

using Ipopt::Index;
using Ipopt::Number;

class ContactQp : public Ipopt::TNLP {
 public:
  ContactQp(const solver::PrimalProblem& problem, double load_factor)
      : problem_(problem), f_(load_factor * problem.load()) {
    // Lower triangle of K, column by column.
    const solver::SparseMatrix& K = problem.stiffness();
    for (int col = 0; col < K.outerSize(); ++col)
      for (solver::SparseMatrix::InnerIterator it(K, col); it; ++it)
        if (it.row() >= col) hessian_.emplace_back(it.row(), col, it.value());
  }

  Eigen::VectorXd solution;
  Ipopt::SolverReturn status = Ipopt::INTERNAL_ERROR;

  bool get_nlp_info(Index& n, Index& m, Index& nnz_jac, Index& nnz_h,
                    IndexStyleEnum& style) override {
    n = problem_.size();
    m = static_cast<Index>(problem_.contact_rows().rows());
    nnz_jac = static_cast<Index>(problem_.contact_rows().nonZeros());
    nnz_h = static_cast<Index>(hessian_.size());
    style = C_STYLE;
    return true;
  }
  bool get_bounds_info(Index n, Number* xl, Number* xu, Index m, Number* gl, Number* gu) override {
    const double inf = 2e19;  // Ipopt's "no bound"
    for (Index i = 0; i < n; ++i) {
      xl[i] = -inf;
      xu[i] = inf;
    }
    for (Index k = 0; k < m; ++k) {
      gl[k] = -inf;
      gu[k] = problem_.gaps()(k);
    }
    return true;
  }
  bool get_starting_point(Index n, bool, Number* x, bool, Number*, Number*, Index, bool,
                          Number*) override {
    for (Index i = 0; i < n; ++i)
      x[i] = 0.0;
    return true;
  }
  bool eval_f(Index n, const Number* x, bool, Number& value) override {
    const Eigen::Map<const Eigen::VectorXd> u(x, n);
    value = 0.5 * u.dot(problem_.stiffness() * u) - f_.dot(u);
    return true;
  }
  bool eval_grad_f(Index n, const Number* x, bool, Number* grad) override {
    const Eigen::Map<const Eigen::VectorXd> u(x, n);
    Eigen::Map<Eigen::VectorXd>(grad, n) = problem_.stiffness() * u - f_;
    return true;
  }
  bool eval_g(Index n, const Number* x, bool, Index m, Number* g) override {
    const Eigen::Map<const Eigen::VectorXd> u(x, n);
    Eigen::Map<Eigen::VectorXd>(g, m) = problem_.contact_rows() * u;
    return true;
  }
  bool eval_jac_g(Index, const Number*, bool, Index, Index, Index* rows, Index* cols,
                  Number* values) override {
    const solver::RowSparseMatrix& A = problem_.contact_rows();
    Index e = 0;
    for (int k = 0; k < A.outerSize(); ++k)
      for (solver::RowSparseMatrix::InnerIterator it(A, k); it; ++it, ++e) {
        if (values)
          values[e] = it.value();
        else {
          rows[e] = k;
          cols[e] = it.col();
        }
      }
    return true;
  }
  bool eval_h(Index, const Number*, bool, Number obj_factor, Index, const Number*, bool, Index,
              Index* rows, Index* cols, Number* values) override {
    for (size_t e = 0; e < hessian_.size(); ++e) {
      if (values)
        values[e] = obj_factor * hessian_[e].value();
      else {
        rows[e] = hessian_[e].row();
        cols[e] = hessian_[e].col();
      }
    }
    return true;
  }
  void finalize_solution(Ipopt::SolverReturn s, Index n, const Number* x, const Number*,
                         const Number*, Index, const Number*, const Number*, Number,
                         const Ipopt::IpoptData*, Ipopt::IpoptCalculatedQuantities*) override {
    status = s;
    solution = Eigen::Map<const Eigen::VectorXd>(x, n);
  }

 private:
  const solver::PrimalProblem& problem_;
  Eigen::VectorXd f_;
  std::vector<Eigen::Triplet<double>> hessian_;
};

}  // namespace

IpoptResult solve_with_ipopt(const solver::Model& model, double load_factor, double tolerance) {
  IpoptResult result;
  const auto start = std::chrono::steady_clock::now();
  const solver::PrimalProblem problem(model, /*factorize_blocks=*/false);
  Ipopt::SmartPtr<ContactQp> qp = new ContactQp(problem, load_factor);
  Ipopt::SmartPtr<Ipopt::IpoptApplication> app = IpoptApplicationFactory();
  app->Options()->SetIntegerValue("print_level", 0);
  app->Options()->SetStringValue("sb", "yes");
  app->Options()->SetNumericValue("tol", tolerance);
  app->Options()->SetStringValue("hessian_constant", "yes");
  app->Options()->SetStringValue("jac_c_constant", "yes");
  app->Options()->SetStringValue("jac_d_constant", "yes");
  app->Options()->SetStringValue("mu_strategy", "adaptive");
  app->Options()->SetIntegerValue("max_iter", 500);
  if (app->Initialize() != Ipopt::Solve_Succeeded) {
    result.status = "Ipopt failed to initialize";
    return result;
  }
  const Ipopt::ApplicationReturnStatus status = app->OptimizeTNLP(qp);
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  result.solved = status == Ipopt::Solve_Succeeded || status == Ipopt::Solved_To_Acceptable_Level;
  result.status =
      result.solved ? "solved" : "Ipopt status " + std::to_string(static_cast<int>(status));
  const Ipopt::SmartPtr<Ipopt::SolveStatistics> statistics = app->Statistics();
  result.iterations = Ipopt::IsValid(statistics) ? statistics->IterationCount() : 0;
  result.u = qp->solution;
  return result;
}

}  // namespace fetic::bench
