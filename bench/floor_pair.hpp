#pragma once
// The paired floor ratio (issue 25, done-when 2): the best dual method and the direct
// floor on the same scene, each as a process of its own, so that a tool which runs the
// two in turn (floor, method, floor, method, ...) and takes the median of the pair
// ratios measures them on the same machine state (docs/BENCHMARKS.md, "The paired floor
// ratio"). Each process generates the scene and builds the model (the same work in both,
// printed as "model s"), then times its part alone and prints it.

#include <string>

#include "scenes/generate_scene.hpp"

namespace fetic::bench {

// `--only method`: solves with `method` (mprgp or feti-c, Dirichlet) and, when
// `working_set_file` is not empty, writes the final working set there (one 0/1 per pair).
int run_method_part(const scenes::GenerateOptions& scene, const std::string& method,
                    const std::string& working_set_file);
// `--only floor`: one CHOLMOD solve of the assembled problem with the working set read
// from `working_set_file` imposed as equalities (solver/direct_floor.hpp).
int run_floor_part(const scenes::GenerateOptions& scene, const std::string& working_set_file);

}  // namespace fetic::bench
