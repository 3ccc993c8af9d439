#pragma once
// The stepper every method implements: start (cold, or warm from an earlier snapshot of
// the same method), step (one iteration), snapshot (the state the app, the renderer and
// the tests all read), status. Expensive set-up (factorizations) happens once, when the
// method is made for a model; start() only resets the iteration, so re-solving at a new
// load factor is cheap.

#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "solver/communicator.hpp"
#include "solver/model.hpp"
#include "solver/stiffness.hpp"

namespace fetic::solver {

enum class MethodKind { SteepestDescent, ConjugateGradient, ActiveSet, Feti, FetiC, Mprgp, FetiDp };
enum class Preconditioner { None, Lumped, Dirichlet };
enum class Status { Running, Converged, Failed };

// Command-line names: "sd", "cg", "active-set", "feti", "feti-c", "mprgp", "feti-dp"; "none",
// "lumped",
// "dirichlet".
const char* to_string(MethodKind method);
const char* to_string(Preconditioner preconditioner);
const char* to_string(Status status);
std::optional<MethodKind> parse_method(const std::string& name);
// Every method: those for contact first (active-set, feti-c, mprgp, feti-dp), then feti, cg, sd.
std::vector<MethodKind> all_methods();
std::optional<Preconditioner> parse_preconditioner(const std::string& name);
bool handles_contact(MethodKind method);
// The dual (FETI) methods, which take a preconditioner and count applications of F.
bool is_dual(MethodKind method);

struct SolveOptions {
  double tolerance = 1e-10;  // relative, see each method
  int max_iterations = 0;    // 0: the method's default cap
  Preconditioner preconditioner = Preconditioner::Dirichlet;
  bool scaling = true;  // stiffness scaling of the FETI preconditioners
  // The dual methods' subdomains (FetiSystem): 0 FETI-1's boxes; -1 FETI-DP's clusters of
  // boxes joined by their corners; N > 0 hybrid clusters of about N boxes (corners.hpp).
  int corner_clusters = 0;
  // FETI-DP: besides the corners, the average of each component over every interface
  // edge inside a cluster primal (plane model; edge_averages.hpp).
  bool edge_averages = false;
  // Dirichlet: factorize K_ii beside K_j (GeneralizedInverse), so that K_j can be cut
  // to its boundary columns at once; off: the preconditioner factorizes K_ii from the
  // whole K_j, kept until then (only to measure the difference: fetic-bench-scale).
  bool shared_interior_factor = true;
  // The subdomain factors' entries below the diagonal kept as floats (half the bytes of
  // the factors' values; the diagonal and the arithmetic stay double). The local solves
  // are then exact for K_j + E_j, |E_j| about 6e-8 |L_j||L_j'|: an option, since it moves
  // the answer by about that much times K_j's condition number (docs/BENCHMARKS.md).
  bool single_factors = false;
  // The Dirichlet preconditioner's interior factors (K_ii) kept as floats the same way.
  // On by default: only the preconditioner solves with them, so the answer is that of
  // the problem itself (GeneralizedInverse::use_single_precision_interior); off only to
  // measure the difference (fetic-bench-scale --only bytes, tests).
  bool single_interior_factors = true;
  // Dirichlet with shared_interior_factor: one factor per subdomain with the boundary last,
  // from whose trailing block F and S_j are applied (solver/boundary_last.hpp), where the
  // boundary holds the fixing DOFs well; off: K_j's and K_ii's factors (only to measure
  // the difference, tests).
  bool boundary_last_factor = true;
};

// A problem found while setting a method up (singular strut, unsupported scene, ...).
class SolverError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct HistoryEntry {
  int iteration = 0;
  double residual = 0.0;                                    // relative, as the method defines it
  int active_set = 0;                                       // contact pairs in the working set
  double error = std::numeric_limits<double>::quiet_NaN();  // vs a reference, when set
  // Applications of the FETI operator F since the start (the dual methods' measure of
  // cost, as PERMON and ESPRESO report it); -1 for the primal methods.
  long long f_applications = -1;
};

// Displacements of one piece of a strut: one FETI subdomain, or a whole strut for the
// primal methods. Pieces of a strut agree on shared nodes only once FETI has converged.
struct Piece {
  int strut = 0;
  NodeBox box;
  std::vector<Vec2> displacement;  // per box node, box-local order
  std::vector<double> rotation;    // frame model: per box node; empty in the others
};

// Appends one node's displacement (and, in the frame model, rotation) to a piece.
void add_node_state(const StrutMesh& mesh, const double* node_dofs, Piece& piece);

struct Snapshot {
  MethodKind method = MethodKind::ActiveSet;
  int iteration = 0;
  Status status = Status::Running;
  std::string message;  // why it failed, or a note
  double load_factor = 1.0;
  double residual = 0.0;
  std::vector<char> in_working_set;  // per contact pair
  std::vector<double> force;         // per contact pair: contact pressure lambda (>= 0)
  std::vector<Piece> pieces;
  // What a warm start of the same method needs: the primal iterate (assembled, free
  // DOFs) or the dual one (all multipliers).
  Eigen::VectorXd primal;
  Eigen::VectorXd dual;

  int active_set_size() const;
};

class Method {
 public:
  virtual ~Method() = default;
  // Fixed when the method is made (a FETI-DP solve says feti-dp whichever core runs it).
  MethodKind kind() const { return kind_; }
  // Starts a solve at `load_factor`, warm from `warm` (a snapshot of the same method on
  // the same model) when given.
  void start(double load_factor, const Snapshot* warm = nullptr);
  // One iteration; does nothing unless the status is Running.
  void step();
  virtual Snapshot snapshot() const = 0;
  // The whole state on rank 0 of a distributed solve (collective: every process calls
  // it); the same as snapshot() in one process.
  Snapshot gathered_snapshot() const { return gathered(snapshot()); }
  // The same from this process' snapshot() taken already (the sweep's final state): no
  // second reconstruction, and rank 0 moves its own pieces into the whole instead of
  // holding them twice (its peak under mpirun, docs/DISTRIBUTED.md).
  virtual Snapshot gathered(Snapshot local) const { return local; }

  Status status() const { return status_; }
  const std::string& message() const { return message_; }
  int iteration() const { return iteration_; }
  int max_iterations() const { return max_iterations_; }
  const std::vector<HistoryEntry>& history() const { return history_; }
  // Per contact pair: in the working set now (snapshot().in_working_set, cheaper where a
  // method overrides it; the same on every process of a distributed solve).
  virtual std::vector<char> working_set() const { return snapshot().in_working_set; }
  // Records, per iteration from now on, the relative displacement error against it.
  void set_reference(std::vector<std::vector<Vec2>> reference) {
    reference_ = std::move(reference);
  }

 protected:
  Method(MethodKind kind, const Model& model, const SolveOptions& options,
         int default_max_iterations);
  // Sets up the initial iterate and records it (history entry 0).
  virtual void begin(const Snapshot* warm) = 0;
  // Performs one iteration and records it.
  virtual void advance() = 0;
  // Appends the history entry of the current iteration; fails past the iteration cap.
  void record(double residual, int active_set);
  // ||u - reference|| / ||reference|| of the current iterate (collective when distributed).
  virtual double reference_error() const;
  const std::vector<std::vector<Vec2>>& reference() const { return reference_; }
  void converge() { status_ = Status::Converged; }
  // Applications of F since the method was made (-1: the method does not apply F).
  virtual long long f_applications() const { return -1; }
  void fail(std::string why);
  // A snapshot with what every method's shares: the method, iteration, status, message,
  // load factor and the last residual; the method adds its state.
  Snapshot snapshot_header() const;

  const Model& model_;
  SolveOptions options_;
  double load_factor_ = 1.0;
  int iteration_ = 0;
  int max_iterations_ = 0;

 private:
  MethodKind kind_;
  Status status_ = Status::Running;
  std::string message_;
  std::vector<HistoryEntry> history_;
  std::vector<std::vector<Vec2>> reference_;
  long long f_applications_at_start_ = 0;
};

// `communicator`: the processes a dual method (feti, feti-c, mprgp) is distributed over; the
// primal methods run in one process.
std::unique_ptr<Method> make_method(MethodKind kind, const Model& model,
                                    const SolveOptions& options,
                                    const Communicator& communicator = Communicator::self());
// Whether `kind` runs distributed over several processes.
bool distributable(MethodKind kind);

// Steps a started method until it stops, or until keep_going() (when given) says no.
void run_to_end(Method& method, const std::function<bool()>& keep_going = {});

// A number for messages: "3.8e-12".
std::string format_number(double value);

// Node displacements per strut (average of the pieces that hold a node).
std::vector<std::vector<Vec2>> strut_displacements(const Model& model, const Snapshot& snapshot);

// Node rotations per strut (frame model; zeros in the others), averaged like the
// displacements.
std::vector<std::vector<double>> strut_rotations(const Model& model, const Snapshot& snapshot);

// The pieces of `snapshot` that hold each strut's nodes (indices into snapshot.pieces).
std::vector<std::vector<int>> pieces_by_strut(const Model& model, const Snapshot& snapshot);
// One strut's node displacements and rotations from its pieces (pieces_by_strut), as the
// forms above give them: the outputs of a large scene made a strut at a time.
std::vector<Vec2> strut_displacements(const Model& model, const Snapshot& snapshot, int strut,
                                      const std::vector<int>& pieces);
std::vector<double> strut_rotations(const Model& model, const Snapshot& snapshot, int strut,
                                    const std::vector<int>& pieces);

// ||u - reference|| / ||reference|| over all strut nodes (absolute when the reference is 0).
double relative_error(const std::vector<std::vector<Vec2>>& u,
                      const std::vector<std::vector<Vec2>>& reference);

}  // namespace fetic::solver
