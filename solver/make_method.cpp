#include "solver/active_set.hpp"
#include "solver/gradient_methods.hpp"
#include "solver/method.hpp"

namespace fetic::solver {

std::unique_ptr<Method> make_method(MethodKind kind, const Model& model,
                                    const SolveOptions& options) {
  switch (kind) {
    case MethodKind::SteepestDescent:
      return std::make_unique<SteepestDescent>(model, options);
    case MethodKind::ConjugateGradient:
      return std::make_unique<ConjugateGradient>(model, options);
    case MethodKind::ActiveSet:
      return std::make_unique<ActiveSet>(model, options);
    case MethodKind::Feti:
    case MethodKind::FetiC:
      break;
  }
  throw SolverError(std::string("method '") + to_string(kind) + "' is not available yet");
}

}  // namespace fetic::solver
