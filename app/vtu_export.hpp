#pragma once
// ParaView output: solver states as VTK unstructured grids, one pair of files per frame
// (an iteration or a load step) in a directory, with a .pvd collection per dataset:
//   struts.pvd   -> struts_0000.vtu, ...    the elements (lines or quadrilaterals)
//   contacts.pvd -> contacts_0000.vtu, ...  one line per contact node pair
// Arrays (docs/SCENES.md "ParaView output"): point data `displacement` (3 components);
// strut cell data `strut`, `element`, `subdomain`, `stress_axial` (+ `stress_sxx`,
// `stress_syy`, `stress_sxy`, `stress_von_mises` in the plane model), `axial_force`;
// contact cell data `contact`, `pair`, `gap`, `force`, `active`, `normal`; field data
// `load_factor`, `iteration`, `residual`, `converged` and the strings `fetic_version`,
// `length_unit`, `force_unit`, `stress_unit`. Frame model: the ends a joint joins share
// one point; point data `rotation`; cell data `bending_moment` (middle),
// `bending_moment_ends` and `end_rotations` (2 components: the element's two ends).

#include <functional>
#include <string>
#include <vector>

#include "app/progress.hpp"
#include "app/vtk_xml.hpp"
#include "solver/method.hpp"

namespace fetic::app {

// The struts' grid is made strut by strut while it is written (a 1e7-unknown scene's
// grid is never whole in memory); it refers to `model` and `state`. `hold_fields`: a
// strut's cell fields are recovered once and held until their arrays are written (up to
// 40 bytes per element) instead of once per array.
VtkStreamedGrid struts_grid(const solver::Model& model, const solver::Snapshot& state,
                            bool hold_fields = false);
VtkGrid contacts_grid(const solver::Model& model, const solver::Snapshot& state);

// Frames written one by one; the .pvd files always list the frames written so far (the
// first frame writes them whole, atomically; each later one appends its entry in place,
// so a series costs time linear in its frames), and an interrupted run leaves a complete
// series. Throws OutputError naming the file on failure.
class VtuSeries {
 public:
  VtuSeries(std::string directory, const solver::Model& model, VtkEncoding encoding);
  // Writes the frame's two .vtu files and updates the .pvd files; `time` is the frame's
  // time value in ParaView. `progress`, when given, takes the progress text instead of
  // a line of the frame's own (a frame written beside another output, SharedProgress).
  void write(const solver::Snapshot& state, double time,
             const std::function<void(const std::string&)>& progress = {});
  // A progress line for a frame that takes over a second to write.
  void show_progress(ProgressMode mode) { progress_ = mode; }
  // Frames from now on hold each strut's cell fields until written (struts_grid): for
  // frames written where memory is free (after `fetic solve` released its method).
  void hold_fields(bool hold) { hold_fields_ = hold; }
  int frames() const { return static_cast<int>(times_.size()); }
  const std::string& directory() const { return directory_; }

 private:
  std::string file_name(const char* dataset, int index) const;

  std::string directory_;
  const solver::Model& model_;
  VtkEncoding encoding_;
  std::vector<double> times_;
  ProgressMode progress_ = ProgressMode::Never;
  bool hold_fields_ = false;
};

}  // namespace fetic::app
