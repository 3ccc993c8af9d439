#pragma once
// The thesis' figures (docs/METHODS.md 5), computed by the running code:
//   2.1  shapes of quadratic forms (positive/negative definite, semidefinite, indefinite)
//   3.2  steepest-descent path on a 2x2 problem      4.3  CG path on the same problem
//   9.2  the solved thesis problem, active contacts in red circles
//   9.3  FETI-C: (a) error against the reference and (b) ||w|| per iteration
//   9.4  active-set size per iteration, active-set method against FETI-C
// and one of fetic's own:
//   S.1  iterations and applications of F against the number of subdomains at fixed
//        H/h: active-set method, FETI-C and MPRGP on generated plane scenes
// The 2x2 problem is a real scene (one bar of two elements, clamped at one end) solved by
// the solver's SD and CG steppers; 9.x run the methods on the thesis scene.

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "render/draw_list.hpp"
#include "render/frame_sequence.hpp"
#include "solver/method.hpp"
#include "solver/model.hpp"

namespace fetic::render {

// --- building blocks, each a whole figure of the given size ---

DrawList figure_quadratic_forms(int width, int height);

// The 2x2 problem: one bar of two elements (E = 210 GPa, A = 1 cm², h = 1 m) clamped at
// one end, 21 kN at the other: K u = f with u in metres.
solver::Model two_dof_bar_model();
struct IteratePath {
  std::string method;                     // "steepest descent", "conjugate gradients"
  Eigen::Matrix2d stiffness;              // K of the free DOFs
  Eigen::Vector2d load;                   // f
  std::vector<Eigen::Vector2d> iterates;  // x0, x1, ... from Snapshot::primal
};
// Runs the solver's stepper of `kind` (sd or cg) on two_dof_bar_model() from u = 0.
IteratePath gradient_path(solver::MethodKind kind, int max_steps = 500);
DrawList figure_gradient_path(const IteratePath& path, const std::string& title, int width,
                              int height);

DrawList figure_solved_scene(const solver::Model& model, const solver::Snapshot& snapshot,
                             const std::string& title, int width, int height);
// 9.3 from a history whose entries carry the error against a reference.
DrawList figure_error_and_search_direction(const std::vector<solver::HistoryEntry>& history,
                                           const std::string& method, int width, int height);
// 9.4: active-set size per iteration of several methods.
struct NamedHistory {
  std::string name;
  std::vector<solver::HistoryEntry> history;
};
DrawList figure_active_set_sizes(const std::vector<NamedHistory>& runs, int width, int height);

// S.1: each method's iterations and applications of F (-1 for the active-set method,
// which does not apply F) per scene, as the subdomains double in both directions.
struct ScalabilityCurve {
  std::string method;
  std::vector<double> subdomains, iterations, f_applications;
  bool converged = true;
};
// Generated plane scenes (2 pairs) from 2x1 up to largest x largest/2 subdomains per strut,
// elements_per_subdomain (H/h) elements per subdomain side.
std::vector<ScalabilityCurve> scalability_runs(int elements_per_subdomain, int largest);
DrawList figure_iterations_by_subdomains(const std::vector<ScalabilityCurve>& curves,
                                         int elements_per_subdomain, int width, int height);

// --- the catalogue ---

struct FigureInfo {
  std::string id;    // "9.3"
  std::string file;  // "fig9_3_fetic_error_and_w.png"
  std::string what;  // one line for the command's output
};
const std::vector<FigureInfo>& figure_catalogue();

struct Figure {
  FigureInfo info;
  std::optional<DrawList> drawing;  // empty when skipped
  std::string note;                 // why it was skipped, or which method drew it
};

// Makes figures by id, running each method on the thesis model at most once.
class FigureMaker {
 public:
  // `thesis` may be null (the scene could not be loaded); `thesis_problem` then says why.
  FigureMaker(const solver::Model* thesis, std::string thesis_problem);
  ~FigureMaker();
  Figure make(const std::string& id, int width, int height);

 private:
  struct Run;
  const Run& run(solver::MethodKind kind);

  const solver::Model* thesis_;
  std::string thesis_problem_;
  std::vector<std::unique_ptr<Run>> runs_;
};

}  // namespace fetic::render
