// The thesis' figures come from the running code: the 2x2 paths are the solver's own SD
// and CG iterates (checked here against the formulas of docs/METHODS.md 4.1-4.2), and every
// figure of the catalogue can be drawn.

#include <catch2/catch.hpp>

#include <Eigen/Dense>

#include "render/figures.hpp"

using namespace fetic;
using namespace fetic::render;

TEST_CASE("the 2x2 problem is one bar of two elements: K = EA/h [2 -1; -1 1]") {
  const IteratePath path = gradient_path(solver::MethodKind::ConjugateGradient);
  const double k = 2.1e11 * 1e-4 / 1.0;
  CHECK(path.stiffness(0, 0) == Approx(2 * k));
  CHECK(path.stiffness(0, 1) == Approx(-k));
  CHECK(path.stiffness(1, 1) == Approx(k));
  CHECK(path.load.isApprox(Eigen::Vector2d(0.0, 21000.0)));
}

TEST_CASE("the steepest-descent path is the solver's, step by step") {
  const IteratePath path = gradient_path(solver::MethodKind::SteepestDescent);
  REQUIRE(path.iterates.size() > 5);
  CHECK(path.iterates.front().isZero());
  Eigen::Vector2d x = Eigen::Vector2d::Zero();
  for (std::size_t i = 1; i < 6; ++i) {  // Def. 3.3: x += (r'r / r'Kr) r
    const Eigen::Vector2d r = path.load - path.stiffness * x;
    x += r.squaredNorm() / r.dot(path.stiffness * r) * r;
    CHECK((path.iterates[i] - x).norm() <= 1e-12 * x.norm());
  }
  const Eigen::Vector2d solution = path.stiffness.ldlt().solve(path.load);
  CHECK((path.iterates.back() - solution).norm() <= 1e-8 * solution.norm());
}

TEST_CASE("conjugate gradients reach the solution of the 2x2 problem in two steps") {
  const IteratePath path = gradient_path(solver::MethodKind::ConjugateGradient);
  const Eigen::Vector2d solution = path.stiffness.ldlt().solve(path.load);
  REQUIRE(path.iterates.size() >= 3);
  CHECK((path.iterates[2] - solution).norm() <= 1e-9 * solution.norm());
  CHECK(path.iterates.size() <= 4);
}

TEST_CASE("every figure of the catalogue can be drawn when the thesis model is there") {
  // A small stand-in for the thesis scene: the figure code is generic over the model.
  const solver::Model model = two_dof_bar_model();
  FigureMaker maker(&model, "");
  for (const FigureInfo& info : figure_catalogue()) {
    const Figure figure = maker.make(info.id, 400, 300);
    INFO(info.id << ": " << figure.note);
    CHECK(figure.info.file == info.file);
    if (info.id.starts_with("9.")) {
      // Without contacts the active-set method may refuse; then the reason is given.
      CHECK((figure.drawing.has_value() || !figure.note.empty()));
    } else {
      REQUIRE(figure.drawing.has_value());
      CHECK(figure.drawing->triangle_count() > 100);
    }
  }
}

TEST_CASE("figures without their scene are skipped with the reason") {
  FigureMaker maker(nullptr, "scenes/thesis.toml: the thesis scene could not be loaded");
  const Figure figure = maker.make("9.3", 400, 300);
  CHECK_FALSE(figure.drawing.has_value());
  CHECK_THAT(figure.note, Catch::Contains("scenes/thesis.toml"));
  CHECK(maker.make("2.1", 400, 300).drawing.has_value());
}

TEST_CASE("9.3 and 9.4 plot the histories they are given") {
  std::vector<solver::HistoryEntry> history;
  for (int i = 0; i <= 6; ++i)
    history.push_back({i, std::pow(10.0, -2.0 * i), 50 - i, std::pow(10.0, -1.5 * i)});
  const DrawList error = figure_error_and_search_direction(history, "FETI-C", 600, 400);
  std::string texts;
  for (const TextItem& text : error.texts())
    texts += text.text + "|";
  CHECK_THAT(texts, Catch::Contains("a) error ‖e‖"));
  CHECK_THAT(texts, Catch::Contains("b) size of the search direction ‖w‖"));
  CHECK_THAT(texts, Catch::Contains("10⁻¹²"));
  const DrawList sizes =
      figure_active_set_sizes({{"active-set method", history}, {"FETI-C", history}}, 600, 400);
  texts.clear();
  for (const TextItem& text : sizes.texts())
    texts += text.text + "|";
  CHECK_THAT(texts, Catch::Contains("FETI-C (6 iterations)"));
  CHECK_THAT(texts, Catch::Contains("Figure 9.4"));
}

TEST_CASE("S.1 runs the three contact methods on the same generated scenes") {
  const std::vector<ScalabilityCurve> curves = scalability_runs(2, 4);
  REQUIRE(curves.size() == 3);
  for (const ScalabilityCurve& curve : curves) {
    INFO(curve.method);
    CHECK(curve.converged);
    REQUIRE(curve.subdomains.size() == 2);  // 2x1 and 4x2 subdomains per strut, 2 pairs
    CHECK(curve.subdomains[0] == 8.0);
    CHECK(curve.subdomains[1] == 32.0);
    for (size_t k = 0; k < curve.iterations.size(); ++k)
      if (curve.method == "active-set")
        CHECK(curve.f_applications[k] == -1.0);  // the primal method does not apply F
      else
        CHECK(curve.f_applications[k] >= curve.iterations[k]);
  }
  const DrawList figure = figure_iterations_by_subdomains(curves, 2, 600, 400);
  std::string texts;
  for (const TextItem& text : figure.texts())
    texts += text.text + "|";
  CHECK_THAT(texts, Catch::Contains("mprgp iterations") &&
                        Catch::Contains("feti-c applications of F") && Catch::Contains("H/h = 2"));
}
