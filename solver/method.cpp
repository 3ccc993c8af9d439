#include "solver/method.hpp"

#include <cmath>
#include <cstdio>

#include "scenes/enum_names.hpp"

namespace fetic::solver {

namespace {

// The names on the command line and in result files; the methods for contact first (in
// the order `fetic bench` measures them), then those for scenes without contacts.
constexpr scenes::EnumName<MethodKind> kMethodNames[] = {{MethodKind::ActiveSet, "active-set"},
                                                         {MethodKind::FetiC, "feti-c"},
                                                         {MethodKind::Mprgp, "mprgp"},
                                                         {MethodKind::FetiDp, "feti-dp"},
                                                         {MethodKind::Feti, "feti"},
                                                         {MethodKind::ConjugateGradient, "cg"},
                                                         {MethodKind::SteepestDescent, "sd"}};
constexpr scenes::EnumName<Preconditioner> kPreconditionerNames[] = {
    {Preconditioner::None, "none"},
    {Preconditioner::Lumped, "lumped"},
    {Preconditioner::Dirichlet, "dirichlet"}};
constexpr scenes::EnumName<Status> kStatusNames[] = {
    {Status::Running, "running"}, {Status::Converged, "converged"}, {Status::Failed, "failed"}};

}  // namespace

const char* to_string(MethodKind method) {
  return scenes::name_of(kMethodNames, method);
}

const char* to_string(Preconditioner preconditioner) {
  return scenes::name_of(kPreconditionerNames, preconditioner);
}

const char* to_string(Status status) {
  return scenes::name_of(kStatusNames, status);
}

std::vector<MethodKind> all_methods() {
  std::vector<MethodKind> methods;
  for (const auto& entry : kMethodNames)
    methods.push_back(entry.value);
  return methods;
}

std::optional<MethodKind> parse_method(const std::string& name) {
  return scenes::value_named(kMethodNames, name);
}

std::optional<Preconditioner> parse_preconditioner(const std::string& name) {
  return scenes::value_named(kPreconditionerNames, name);
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

Method::Method(MethodKind kind, const Model& model, const SolveOptions& options,
               int default_max_iterations)
    : model_(model), options_(options), kind_(kind) {
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

void add_node_state(const StrutMesh& mesh, const double* node_dofs, Piece& piece) {
  piece.displacement.push_back(node_displacement(mesh, node_dofs));
  if (mesh.dofs_per_node == 3) piece.rotation.push_back(node_rotation(mesh, node_dofs));
}

std::vector<std::vector<int>> pieces_by_strut(const Model& model, const Snapshot& snapshot) {
  std::vector<std::vector<int>> pieces(model.struts.size());
  for (size_t p = 0; p < snapshot.pieces.size(); ++p)
    pieces[static_cast<size_t>(snapshot.pieces[p].strut)].push_back(static_cast<int>(p));
  return pieces;
}

namespace {

// The average over the pieces of `strut` of a per-box-node value (`of` gives a piece's).
template <typename T, typename Values>
std::vector<T> strut_average(const Model& model, const Snapshot& snapshot, int strut,
                             const std::vector<int>& pieces, const T& zero, Values of) {
  const StrutMesh& mesh = model.struts[static_cast<size_t>(strut)];
  std::vector<T> sum(static_cast<size_t>(mesh.node_count()), zero);
  std::vector<int> count(sum.size(), 0);
  for (int p : pieces) {
    const Piece& piece = snapshot.pieces[static_cast<size_t>(p)];
    const auto& values = of(piece);
    if (values.empty()) continue;
    for (int i = piece.box.i0; i <= piece.box.i1; ++i)
      for (int k = piece.box.k0; k <= piece.box.k1; ++k) {
        const auto node = static_cast<size_t>(mesh.node(i, k));
        sum[node] += values[static_cast<size_t>(piece.box.local(i, k))];
        count[node] += 1;
      }
  }
  for (size_t n = 0; n < sum.size(); ++n)
    if (count[n] > 1) sum[n] /= count[n];
  return sum;
}

// of_strut(s, the pieces of strut s) for every strut s.
template <typename T, typename OfStrut>
std::vector<T> per_strut(const Model& model, const Snapshot& snapshot, OfStrut of_strut) {
  const auto pieces = pieces_by_strut(model, snapshot);
  std::vector<T> values;
  values.reserve(model.struts.size());
  for (size_t s = 0; s < model.struts.size(); ++s)
    values.push_back(of_strut(static_cast<int>(s), pieces[s]));
  return values;
}

}  // namespace

std::vector<Vec2> strut_displacements(const Model& model, const Snapshot& snapshot, int strut,
                                      const std::vector<int>& pieces) {
  std::vector<Vec2> u = strut_average<Vec2>(
      model, snapshot, strut, pieces, Vec2::Zero(),
      [](const Piece& piece) -> const std::vector<Vec2>& { return piece.displacement; });
  // Clamped nodes are exactly at rest; total FETI holds them by multipliers, which leaves
  // rounding-level displacements (1e-19) there.
  for (int node : model.clamped_nodes[static_cast<size_t>(strut)])
    u[static_cast<size_t>(node)].setZero();
  return u;
}

std::vector<double> strut_rotations(const Model& model, const Snapshot& snapshot, int strut,
                                    const std::vector<int>& pieces) {
  return strut_average<double>(
      model, snapshot, strut, pieces, 0.0,
      [](const Piece& piece) -> const std::vector<double>& { return piece.rotation; });
}

std::vector<std::vector<Vec2>> strut_displacements(const Model& model, const Snapshot& snapshot) {
  return per_strut<std::vector<Vec2>>(model, snapshot, [&](int s, const std::vector<int>& pieces) {
    return strut_displacements(model, snapshot, s, pieces);
  });
}

std::vector<std::vector<double>> strut_rotations(const Model& model, const Snapshot& snapshot) {
  return per_strut<std::vector<double>>(model, snapshot,
                                        [&](int s, const std::vector<int>& pieces) {
                                          return strut_rotations(model, snapshot, s, pieces);
                                        });
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
