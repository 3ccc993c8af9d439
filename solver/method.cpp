#include "solver/method.hpp"

#include <cmath>
#include <cstdio>

namespace fetic::solver {

const char* to_string(MethodKind method) {
  switch (method) {
    case MethodKind::SteepestDescent:
      return "sd";
    case MethodKind::ConjugateGradient:
      return "cg";
    case MethodKind::ActiveSet:
      return "active-set";
    case MethodKind::Feti:
      return "feti";
    case MethodKind::FetiC:
      return "feti-c";
    case MethodKind::Mprgp:
      return "mprgp";
    case MethodKind::FetiDp:
      return "feti-dp";
  }
  return "?";
}

const char* to_string(Preconditioner preconditioner) {
  switch (preconditioner) {
    case Preconditioner::None:
      return "none";
    case Preconditioner::Lumped:
      return "lumped";
    case Preconditioner::Dirichlet:
      return "dirichlet";
  }
  return "?";
}

const char* to_string(Status status) {
  switch (status) {
    case Status::Running:
      return "running";
    case Status::Converged:
      return "converged";
    case Status::Failed:
      return "failed";
  }
  return "?";
}

std::optional<MethodKind> parse_method(const std::string& name) {
  for (MethodKind kind :
       {MethodKind::SteepestDescent, MethodKind::ConjugateGradient, MethodKind::ActiveSet,
        MethodKind::Feti, MethodKind::FetiC, MethodKind::Mprgp, MethodKind::FetiDp})
    if (name == to_string(kind)) return kind;
  return std::nullopt;
}

std::optional<Preconditioner> parse_preconditioner(const std::string& name) {
  for (Preconditioner p : {Preconditioner::None, Preconditioner::Lumped, Preconditioner::Dirichlet})
    if (name == to_string(p)) return p;
  return std::nullopt;
}

bool distributable(MethodKind method) {
  return is_dual(method);
}

bool handles_contact(MethodKind method) {
  return method == MethodKind::ActiveSet || method == MethodKind::FetiC ||
         method == MethodKind::Mprgp || method == MethodKind::FetiDp;
}

bool is_dual(MethodKind method) {
  return method == MethodKind::Feti || method == MethodKind::FetiC || method == MethodKind::Mprgp ||
         method == MethodKind::FetiDp;
}

int Snapshot::active_set_size() const {
  int count = 0;
  for (char in : in_working_set)
    count += in ? 1 : 0;
  return count;
}

Method::Method(const Model& model, const SolveOptions& options, int default_max_iterations)
    : model_(model), options_(options) {
  max_iterations_ = options.max_iterations > 0 ? options.max_iterations : default_max_iterations;
}

void Method::start(double load_factor, const Snapshot* warm) {
  load_factor_ = load_factor;
  iteration_ = 0;
  status_ = Status::Running;
  message_.clear();
  history_.clear();
  f_applications_at_start_ = f_applications();
  if (warm && warm->method != kind()) warm = nullptr;
  begin(warm);
}

void Method::step() {
  if (status_ == Status::Running) advance();
}

void Method::record(double residual, int active_set) {
  HistoryEntry entry{iteration_, residual, active_set};
  const long long applied = f_applications();
  if (applied >= 0) entry.f_applications = applied - f_applications_at_start_;
  if (!reference_.empty()) entry.error = reference_error();
  history_.push_back(entry);
  if (!std::isfinite(residual)) {
    fail("the residual became " + std::string(std::isnan(residual) ? "NaN" : "infinite") +
         " at iteration " + std::to_string(iteration_));
  } else if (status_ == Status::Running && iteration_ >= max_iterations_) {
    fail("no convergence within " + std::to_string(max_iterations_) +
         " iterations (relative residual " + format_number(residual) + ", tolerance " +
         format_number(options_.tolerance) + ")");
  }
}

double Method::reference_error() const {
  return relative_error(strut_displacements(model_, snapshot()), reference_);
}

void Method::fail(std::string why) {
  status_ = Status::Failed;
  message_ = std::move(why);
}

std::string format_number(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.3g", value);
  return buffer;
}

void run_to_end(Method& method, const std::function<bool()>& keep_going) {
  while (method.status() == Status::Running && (!keep_going || keep_going()))
    method.step();
}

std::vector<std::vector<Vec2>> strut_displacements(const Model& model, const Snapshot& snapshot) {
  std::vector<std::vector<Vec2>> sum(model.struts.size());
  std::vector<std::vector<int>> count(model.struts.size());
  for (size_t s = 0; s < model.struts.size(); ++s) {
    sum[s].assign(model.struts[s].node_count(), Vec2::Zero());
    count[s].assign(model.struts[s].node_count(), 0);
  }
  for (const Piece& piece : snapshot.pieces) {
    const StrutMesh& mesh = model.struts[piece.strut];
    for (int i = piece.box.i0; i <= piece.box.i1; ++i)
      for (int k = piece.box.k0; k <= piece.box.k1; ++k) {
        sum[piece.strut][mesh.node(i, k)] += piece.displacement[piece.box.local(i, k)];
        count[piece.strut][mesh.node(i, k)] += 1;
      }
  }
  for (size_t s = 0; s < sum.size(); ++s)
    for (size_t n = 0; n < sum[s].size(); ++n)
      if (count[s][n] > 1) sum[s][n] /= count[s][n];
  // Clamped nodes are exactly at rest; total FETI holds them by multipliers, which leaves
  // rounding-level displacements (1e-19) there.
  for (size_t s = 0; s < sum.size(); ++s)
    for (int node : model.clamped_nodes[s])
      sum[s][static_cast<size_t>(node)].setZero();
  return sum;
}

void add_node_state(const StrutMesh& mesh, const double* node_dofs, Piece& piece) {
  piece.displacement.push_back(node_displacement(mesh, node_dofs));
  if (mesh.dofs_per_node == 3) piece.rotation.push_back(node_rotation(mesh, node_dofs));
}

std::vector<std::vector<double>> strut_rotations(const Model& model, const Snapshot& snapshot) {
  std::vector<std::vector<double>> sum(model.struts.size());
  std::vector<std::vector<int>> count(model.struts.size());
  for (size_t s = 0; s < model.struts.size(); ++s) {
    sum[s].assign(model.struts[s].node_count(), 0.0);
    count[s].assign(model.struts[s].node_count(), 0);
  }
  for (const Piece& piece : snapshot.pieces) {
    if (piece.rotation.empty()) continue;
    const StrutMesh& mesh = model.struts[piece.strut];
    for (int i = piece.box.i0; i <= piece.box.i1; ++i)
      for (int k = piece.box.k0; k <= piece.box.k1; ++k) {
        sum[piece.strut][mesh.node(i, k)] += piece.rotation[piece.box.local(i, k)];
        count[piece.strut][mesh.node(i, k)] += 1;
      }
  }
  for (size_t s = 0; s < sum.size(); ++s)
    for (size_t n = 0; n < sum[s].size(); ++n)
      if (count[s][n] > 1) sum[s][n] /= count[s][n];
  return sum;
}

double relative_error(const std::vector<std::vector<Vec2>>& u,
                      const std::vector<std::vector<Vec2>>& reference) {
  double difference = 0.0, size = 0.0;
  for (size_t s = 0; s < u.size() && s < reference.size(); ++s)
    for (size_t n = 0; n < u[s].size() && n < reference[s].size(); ++n) {
      difference += (u[s][n] - reference[s][n]).squaredNorm();
      size += reference[s][n].squaredNorm();
    }
  return size > 0.0 ? std::sqrt(difference / size) : std::sqrt(difference);
}

Snapshot Method::snapshot_header() const {
  Snapshot s;
  s.method = kind();
  s.iteration = iteration_;
  s.status = status();
  s.message = message();
  s.load_factor = load_factor_;
  s.residual = history().empty() ? 0.0 : history().back().residual;
  return s;
}

}  // namespace fetic::solver
