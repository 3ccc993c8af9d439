#include "solver/active_set.hpp"
#include "solver/feti_c.hpp"
#include "solver/gradient_methods.hpp"
#include "solver/method.hpp"
#include "solver/mprgp.hpp"
#include "solver/pcpg.hpp"

namespace fetic::solver {

std::unique_ptr<Method> make_method(MethodKind kind, const Model& model,
                                    const SolveOptions& options, const Communicator& communicator) {
  if (communicator.distributed() && !distributable(kind))
    throw SolverError(std::string("--method ") + to_string(kind) +
                      " runs in one process; under mpirun use feti, feti-c, mprgp or feti-dp");
  switch (kind) {
    case MethodKind::SteepestDescent:
      return std::make_unique<SteepestDescent>(model, options);
    case MethodKind::ConjugateGradient:
      return std::make_unique<ConjugateGradient>(model, options);
    case MethodKind::ActiveSet:
      return std::make_unique<ActiveSet>(model, options);
    case MethodKind::Feti:
      return std::make_unique<Pcpg>(model, options, communicator);
    case MethodKind::FetiC:
      return std::make_unique<FetiC>(model, options, communicator);
    case MethodKind::Mprgp:
      return std::make_unique<Mprgp>(model, options, communicator);
    case MethodKind::FetiDp: {
      // FETI-DP: the boxes joined by their corners (corners.hpp); PCPG without contacts,
      // MPRGP with them. Both report themselves as feti-dp.
      SolveOptions dp = options;
      if (dp.corner_clusters == 0) dp.corner_clusters = -1;
      if (model.pairs.empty()) return std::make_unique<Pcpg>(model, dp, communicator);
      return std::make_unique<Mprgp>(model, dp, communicator);
    }
  }
  throw SolverError(std::string("unknown method '") + to_string(kind) + "'");
}

}  // namespace fetic::solver
