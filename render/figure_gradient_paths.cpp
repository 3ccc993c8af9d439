// Figures 3.2 and 4.3: the iterates of the solver's steepest-descent and CG steppers on a
// real 2-DOF scene, over the contours of its energy f(u) = 1/2 u'K u - f'u.

#include <algorithm>
#include <cmath>
#include <numbers>

#include <Eigen/Eigenvalues>

#include "render/colormap.hpp"
#include "render/figures.hpp"
#include "render/plot.hpp"
#include "render/text_format.hpp"
#include "render/view.hpp"
#include "scenes/scene.hpp"
#include "solver/primal_problem.hpp"

namespace fetic::render {
namespace {

constexpr double kMillimetres = 1e3;

double energy(const IteratePath& path, const Eigen::Vector2d& u) {
  return 0.5 * u.dot(path.stiffness * u) - path.load.dot(u);
}

// Points of the level set f(u) = f(u*) + c (an ellipse around u*), in millimetres.
std::vector<std::pair<double, double>> level_set(const IteratePath& path, double c) {
  // The closed form for 2x2 (computeDirect): the iterative solver's template was half of
  // this file's compile time (13.7 -> 7.2 CPU-s at -O3).
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eigen;
  eigen.computeDirect(path.stiffness);
  const Eigen::Vector2d center = path.stiffness.ldlt().solve(path.load);
  std::vector<std::pair<double, double>> points;
  constexpr int kSegments = 120;
  for (int s = 0; s <= kSegments; ++s) {
    const double angle = 2.0 * std::numbers::pi * s / kSegments;
    const Eigen::Vector2d unit(std::cos(angle) / std::sqrt(eigen.eigenvalues()[0]),
                               std::sin(angle) / std::sqrt(eigen.eigenvalues()[1]));
    const Eigen::Vector2d u = center + std::sqrt(2.0 * c) * eigen.eigenvectors() * unit;
    points.emplace_back(kMillimetres * u.x(), kMillimetres * u.y());
  }
  return points;
}

}  // namespace

solver::Model two_dof_bar_model() {
  scenes::Scene scene;
  scene.path = "(built-in 2x2 problem)";
  scene.title = "One bar, two elements, clamped at the left";
  scene.model = scenes::ModelKind::Bar;
  scenes::Strut bar;
  bar.name = "bar";
  bar.from = {0.0, 0.0};
  bar.to = {2.0, 0.0};
  bar.E = 2.1e11;
  bar.area = 1.0e-4;
  bar.elements = 2;
  bar.subdomains = 1;
  bar.fixed_from = true;
  scene.struts.push_back(bar);
  scenes::Load load;
  load.strut = 0;
  load.at = scenes::StrutEnd::To;
  load.force = {21000.0, 0.0};
  scene.loads.push_back(load);
  return solver::build_model(scene);
}

IteratePath gradient_path(solver::MethodKind kind, int max_steps) {
  const solver::Model model = two_dof_bar_model();
  const solver::PrimalProblem problem(model);
  IteratePath path;
  path.method =
      kind == solver::MethodKind::SteepestDescent ? "steepest descent" : "conjugate gradients";
  path.stiffness = Eigen::Matrix2d(problem.stiffness());
  path.load = problem.load();
  solver::SolveOptions options;
  options.max_iterations = max_steps;
  const auto method = solver::make_method(kind, model, options);
  method->start(1.0);
  const auto record = [&] {
    const Eigen::VectorXd& u = method->snapshot().primal;
    path.iterates.emplace_back(u[0], u[1]);
  };
  record();
  while (method->status() == solver::Status::Running) {
    method->step();
    record();
  }
  return path;
}

DrawList figure_gradient_path(const IteratePath& path, const std::string& title, int width,
                              int height) {
  DrawList list;
  const float text = base_text_size(width, height);
  const Eigen::Vector2d solution = path.stiffness.ldlt().solve(path.load);
  const double lowest = energy(path, solution);
  const double c0 = std::max(energy(path, path.iterates.front()) - lowest, 1e-300);

  // Range: the level set through the start, and a little room.
  const Eigen::Matrix2d inverse = path.stiffness.inverse();
  const double reach_x = 1.12 * std::sqrt(2.0 * c0 * inverse(0, 0)) * kMillimetres;
  const double reach_y = 1.12 * std::sqrt(2.0 * c0 * inverse(1, 1)) * kMillimetres;
  PlotSpec spec;
  spec.frame = {0.0f, 0.0f, static_cast<float>(width), static_cast<float>(height)};
  spec.title = title;
  spec.text_size = text;
  spec.equal_aspect = true;
  spec.x = {"u₁: displacement of the middle node [mm]", kMillimetres * solution.x() - reach_x,
            kMillimetres * solution.x() + reach_x, false, false};
  spec.y = {"u₂: displacement of the loaded end [mm]", kMillimetres * solution.y() - reach_y,
            kMillimetres * solution.y() + reach_y, false, false};
  spec.grid = false;
  spec.legend = Corner::BottomRight;
  const PlotArea area = draw_axes(list, spec);

  // Contours through the first iterates (SD steps end tangent to them), then finer ones.
  std::vector<double> levels;
  for (std::size_t k = 0; k < std::min<std::size_t>(path.iterates.size(), 6); ++k)
    levels.push_back(energy(path, path.iterates[k]) - lowest);
  for (double c = c0 * 0.02; c < c0; c *= 3.0)
    levels.push_back(c);
  levels.push_back(1.6 * c0);
  std::sort(levels.begin(), levels.end());
  levels.erase(std::unique(levels.begin(), levels.end(),
                           [&](double a, double b) { return std::abs(a - b) < 1e-9 * c0; }),
               levels.end());
  Series contour;
  contour.width = 1.2f;
  for (double c : levels) {
    if (!(c > 1e-12 * c0)) continue;
    contour.x.clear();
    contour.y.clear();
    for (const auto& [x, y] : level_set(path, c)) {
      contour.x.push_back(x);
      contour.y.push_back(y);
    }
    contour.color = with_alpha(sequential(0.15 + 0.7 * std::sqrt(c / (1.6 * c0))), 200);
    draw_series(list, area, contour);
  }

  Series iterates;
  iterates.name = path.method + " (" + std::to_string(path.iterates.size() - 1) + " iterations)";
  iterates.color = series_color(1);
  iterates.width = 2.2f;
  iterates.markers = true;
  for (const Eigen::Vector2d& u : path.iterates) {
    iterates.x.push_back(kMillimetres * u.x());
    iterates.y.push_back(kMillimetres * u.y());
  }
  draw_series(list, area, iterates);
  const char* subscripts[] = {"₀", "₁", "₂", "₃"};
  for (std::size_t k = 0; k < std::min<std::size_t>(path.iterates.size(), 4); ++k) {
    const Point p = area.to_pixel(iterates.x[k], iterates.y[k]);
    if (k > 0 &&
        length(p - area.to_pixel(solution.x() * kMillimetres, solution.y() * kMillimetres)) < text)
      continue;
    list.text(std::string("x") + subscripts[k], p + Point{0.5f * text, -0.3f * text}, text,
              palette::ink, HAlign::Left, VAlign::Bottom);
  }
  Series answer;
  answer.name = "solution u* = K⁻¹f";
  answer.color = palette::contact;
  answer.width = 2.5f;
  answer.markers = true;
  answer.x = {kMillimetres * solution.x()};
  answer.y = {kMillimetres * solution.y()};
  draw_series(list, area, answer);
  Series contour_key;
  contour_key.name = "contours of f(u) = ½u'Ku − f'u";
  contour_key.color = sequential(0.5);
  contour_key.width = 1.2f;
  draw_legend(list, area, {iterates, answer, contour_key}, spec.legend, text);
  return list;
}

}  // namespace fetic::render
