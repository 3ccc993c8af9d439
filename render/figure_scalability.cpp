// The scalability figure: iterations (and applications of F) against the number of
// subdomains at fixed H/h, for the active-set method, FETI-C and MPRGP, on generated
// plane scenes (fetic generate) - the same family as fetic-bench-scale's table 2a.

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "render/colormap.hpp"
#include "render/figures.hpp"
#include "render/plot.hpp"
#include "render/view.hpp"
#include "scenes/generate_scene.hpp"

namespace fetic::render {

std::vector<ScalabilityCurve> scalability_runs(int elements_per_subdomain, int largest) {
  const solver::MethodKind kinds[] = {solver::MethodKind::ActiveSet, solver::MethodKind::FetiC,
                                      solver::MethodKind::Mprgp};
  std::vector<ScalabilityCurve> curves;
  for (solver::MethodKind kind : kinds)
    curves.push_back({solver::to_string(kind), {}, {}, {}, true});
  for (int along = 2; along <= largest; along *= 2) {
    scenes::GenerateOptions options;
    options.model = scenes::ModelKind::Plane;
    options.pairs = 2;
    options.subdomains = along;
    options.subdomains_across = std::max(1, along / 2);
    options.elements = along * elements_per_subdomain;
    options.elements_across = options.subdomains_across * elements_per_subdomain;
    const solver::Model model = solver::build_model(scenes::generate_scene(options));
    const double subdomains = 2.0 * options.pairs * along * options.subdomains_across;
    for (size_t m = 0; m < curves.size(); ++m) {
      const auto method = solver::make_method(kinds[m], model, solver::SolveOptions{});
      method->start(1.0);
      solver::run_to_end(*method);
      ScalabilityCurve& curve = curves[m];
      curve.converged = curve.converged && method->status() == solver::Status::Converged;
      curve.subdomains.push_back(subdomains);
      curve.iterations.push_back(method->iteration());
      curve.f_applications.push_back(static_cast<double>(method->history().back().f_applications));
    }
  }
  return curves;
}

DrawList figure_iterations_by_subdomains(const std::vector<ScalabilityCurve>& curves,
                                         int elements_per_subdomain, int width, int height) {
  DrawList list;
  const float text = base_text_size(width, height);
  list.text("Iterations against subdomains at H/h = " + std::to_string(elements_per_subdomain) +
                " (plane struts, Dirichlet preconditioner)",
            {0.5f * static_cast<float>(width), 0.5f * text}, text, palette::ink, HAlign::Center,
            VAlign::Top, true);
  PlotSpec spec;
  spec.frame = {0.0f, 2.0f * text, static_cast<float>(width), static_cast<float>(height)};
  spec.text_size = text;
  // The x axis spans the data (8 to 512 subdomains) with a little room, not whole decades
  // (10^0 to 10^3 would leave most of the plot empty).
  double fewest = std::numeric_limits<double>::infinity(), most = 0.0;
  for (const ScalabilityCurve& curve : curves)
    for (const double s : curve.subdomains) {
      fewest = std::min(fewest, s);
      most = std::max(most, s);
    }
  const bool any = most > 0.0 && std::isfinite(fewest);
  spec.x = {"subdomains (4 plane struts of 2x1, 4x2, 8x4, ... subdomains)",
            any ? fewest / 1.6 : std::nan(""), any ? most * 1.6 : std::nan(""), true, false};
  spec.y = {"iterations, applications of F", 0.0, std::nan(""), false, true};
  spec.legend = Corner::TopLeft;
  for (size_t c = 0; c < curves.size(); ++c) {
    const ScalabilityCurve& curve = curves[c];
    const std::string mark = curve.converged ? "" : " (not converged)";
    Series iterations;
    iterations.name = curve.method + " iterations" + mark;
    iterations.color = series_color(static_cast<int>(c));
    iterations.width = 2.4f;
    iterations.markers = true;
    iterations.x = curve.subdomains;
    iterations.y = curve.iterations;
    spec.series.push_back(iterations);
    if (curve.f_applications.empty() || curve.f_applications.front() < 0.0) continue;
    Series applied = iterations;
    applied.name = curve.method + " applications of F" + mark;
    applied.width = 1.2f;
    applied.y = curve.f_applications;
    spec.series.push_back(applied);
  }
  list.append(draw_plot(spec));
  return list;
}

}  // namespace fetic::render
