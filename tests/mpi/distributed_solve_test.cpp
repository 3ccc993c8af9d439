// Run under mpirun with any number of processes: every scene is solved twice by every
// process - once in that process alone (Communicator::self(), the serial solve) and once
// distributed over all of them (Communicator::world()) - and rank 0 compares the two:
// displacements and contact forces to a relative 1e-10, the same working set, the same
// status and the same iteration count (the scalar products are summed exactly, so no
// decision depends on how the rows are split among the processes). Scenes: the bundled ones, random
// bar scenes (opposing pairs and chains with floating struts held only by contacts), random plane
// scenes, random frame scenes (rotations compared too; a floating beam is a group the
// equality rows leave free), random contact-free scenes for FETI-1, and warm-started load
// sweeps.
//
// A plain program rather than Catch2: a failed assertion on one process must not leave
// the others waiting in a collective, so every process runs every case to its end and
// only rank 0 judges. Exit status 0 when every case agrees, 1 otherwise (on all ranks).

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "scenes/load_scene.hpp"
#include "solver/communicator.hpp"
#include "solver/feti_method.hpp"
#include "solver/load_sweep.hpp"
#include "solver/method.hpp"
#include "solver/model.hpp"
#include "tests/support/random_frames.hpp"
#include "tests/support/random_scenes.hpp"

namespace {

using fetic::solver::Communicator;
using fetic::solver::MethodKind;
using fetic::solver::Snapshot;

struct Case {
  std::string name;
  std::string text;  // TOML
  MethodKind method = MethodKind::FetiC;
  fetic::solver::Preconditioner preconditioner = fetic::solver::Preconditioner::Dirichlet;
  std::vector<double> load_factors{1.0};
};

std::string read_file(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

double relative_difference(const std::vector<double>& a, const std::vector<double>& b) {
  double scale = 0.0, difference = 0.0;
  for (size_t i = 0; i < a.size() && i < b.size(); ++i) {
    scale = std::max(scale, std::abs(a[i]));
    difference = std::max(difference, std::abs(a[i] - b[i]));
  }
  if (a.size() != b.size()) return INFINITY;
  return scale > 0.0 ? difference / scale : difference;
}

std::vector<double> flat_displacements(const fetic::solver::Model& model, const Snapshot& s) {
  std::vector<double> flat;
  for (const auto& strut : fetic::solver::strut_displacements(model, s))
    for (const auto& u : strut) {
      flat.push_back(u.x());
      flat.push_back(u.y());
    }
  return flat;
}

// Frame model: every piece's node rotations, in subdomain order (empty in the others).
std::vector<double> flat_rotations(const Snapshot& s) {
  std::vector<double> flat;
  for (const auto& piece : s.pieces)
    flat.insert(flat.end(), piece.rotation.begin(), piece.rotation.end());
  return flat;
}

struct Outcome {
  std::vector<Snapshot> states;  // one per load factor (gathered)
  std::vector<int> iterations;
};

Outcome solve(const Case& c, const fetic::solver::Model& model, const Communicator& processes) {
  fetic::solver::SolveOptions options;
  options.preconditioner = c.preconditioner;
  auto method = fetic::solver::make_method(c.method, model, options, processes);
  Outcome outcome;
  fetic::solver::SweepDriver driver(*method);  // the warm starts of fetic solve
  for (double t : c.load_factors) {
    driver.solve(t);
    outcome.states.push_back(method->gathered_snapshot());
    outcome.iterations.push_back(method->iteration());
  }
  return outcome;
}

// Rank 0's verdict on one case; "" when the distributed solve agrees with the serial one.
std::string compare(const Case& c, const fetic::solver::Model& model, const Outcome& serial,
                    const Outcome& distributed) {
  std::ostringstream why;
  for (size_t step = 0; step < c.load_factors.size(); ++step) {
    const Snapshot& a = serial.states[step];
    const Snapshot& b = distributed.states[step];
    const std::string at = " at load factor " + std::to_string(c.load_factors[step]);
    if (a.status != b.status)
      why << "status " << to_string(a.status) << " vs " << to_string(b.status) << at << "; ";
    // Exact scalar products make every decision independent of the number of processes:
    // the same iterations, not just within one.
    if (serial.iterations[step] != distributed.iterations[step])
      why << "iterations " << serial.iterations[step] << " vs " << distributed.iterations[step]
          << at << "; ";
    if (a.in_working_set != b.in_working_set) why << "different active sets" << at << "; ";
    const double du =
        relative_difference(flat_displacements(model, a), flat_displacements(model, b));
    if (!(du <= 1e-10)) why << "displacements differ by " << du << at << "; ";
    const double dr = relative_difference(flat_rotations(a), flat_rotations(b));
    if (!(dr <= 1e-10)) why << "rotations differ by " << dr << at << "; ";
    const double df = relative_difference(a.force, b.force);
    if (!(df <= 1e-10)) why << "contact forces differ by " << df << at << "; ";
  }
  return why.str();
}

std::vector<Case> cases(const std::string& scenes_dir) {
  std::vector<Case> list;
  for (const char* name : {"thesis.toml", "two_bars.toml", "chain.toml", "plane_pair.toml"}) {
    list.push_back({name, read_file(scenes_dir + "/" + name)});
    list.push_back({std::string(name) + " (lumped)", read_file(scenes_dir + "/" + name),
                    MethodKind::FetiC, fetic::solver::Preconditioner::Lumped});
  }
  list.push_back(
      {"cantilevers.toml (feti)", read_file(scenes_dir + "/cantilevers.toml"), MethodKind::Feti});
  list.push_back({"thesis.toml, load sweep 0.5:1.5:6", read_file(scenes_dir + "/thesis.toml"),
                  MethodKind::FetiC, fetic::solver::Preconditioner::Dirichlet,
                  fetic::solver::load_steps(0.5, 1.5, 6)});
  list.push_back({"chain.toml, load sweep 0:2:5", read_file(scenes_dir + "/chain.toml"),
                  MethodKind::FetiC, fetic::solver::Preconditioner::Dirichlet,
                  fetic::solver::load_steps(0.0, 2.0, 5)});
  std::mt19937 rng(20261201);
  for (int i = 0; i < 40; ++i)
    list.push_back({"random bar scene " + std::to_string(i), fetic::testing::random_bar_scene(rng),
                    MethodKind::FetiC,
                    i % 3 == 0 ? fetic::solver::Preconditioner::None
                               : fetic::solver::Preconditioner::Dirichlet});
  for (int i = 0; i < 24; ++i)
    list.push_back({"random plane scene " + std::to_string(i),
                    fetic::testing::random_plane_pairs(rng, 1 + i % 3), MethodKind::FetiC,
                    i % 2 == 0 ? fetic::solver::Preconditioner::Dirichlet
                               : fetic::solver::Preconditioner::Lumped});
  for (int i = 0; i < 12; ++i)
    list.push_back({"random contact-free scene " + std::to_string(i),
                    fetic::testing::random_contact_free_scene(rng), MethodKind::Feti});
  // MPRGP: its face projector, power method, SMALBE groups (random bar scenes hold some
  // struts only by contacts) and warm starts.
  for (const char* name : {"thesis.toml", "two_bars.toml", "chain.toml", "plane_pair.toml"})
    list.push_back(
        {std::string(name) + " (mprgp)", read_file(scenes_dir + "/" + name), MethodKind::Mprgp});
  list.push_back({"thesis.toml (mprgp, lumped)", read_file(scenes_dir + "/thesis.toml"),
                  MethodKind::Mprgp, fetic::solver::Preconditioner::Lumped});
  list.push_back({"chain.toml (mprgp), load sweep 0:2:5", read_file(scenes_dir + "/chain.toml"),
                  MethodKind::Mprgp, fetic::solver::Preconditioner::Dirichlet,
                  fetic::solver::load_steps(0.0, 2.0, 5)});
  for (int i = 0; i < 16; ++i)
    list.push_back({"random bar scene (mprgp) " + std::to_string(i),
                    fetic::testing::random_bar_scene(rng), MethodKind::Mprgp,
                    i % 4 == 0 ? fetic::solver::Preconditioner::None
                               : fetic::solver::Preconditioner::Dirichlet});
  for (int i = 0; i < 8; ++i)
    list.push_back({"random plane scene (mprgp) " + std::to_string(i),
                    fetic::testing::random_plane_pairs(rng, 1 + i % 3), MethodKind::Mprgp});
  // Frames: free motions from the replicated decomposition, rotations gathered.
  for (const char* name :
       {"frame_post_on_beam.toml", "frame_apex_stop.toml", "frame_portal_sway.toml",
        "frame_beam_on_contacts.toml", "frame_truss_bridge.toml", "frame_scaffold.toml"})
    for (MethodKind method : {MethodKind::FetiC, MethodKind::Mprgp})
      list.push_back({std::string(name) + " (" + to_string(method) + ")",
                      read_file(scenes_dir + "/" + name), method});
  list.push_back({"frame_portal_sway.toml, load sweep 0:2:5",
                  read_file(scenes_dir + "/frame_portal_sway.toml"), MethodKind::FetiC,
                  fetic::solver::Preconditioner::Dirichlet,
                  fetic::solver::load_steps(0.0, 2.0, 5)});
  using fetic::testing::FrameKind;
  const FrameKind kinds[] = {FrameKind::PostOnBeam, FrameKind::ApexOnStop, FrameKind::PortalOnStop,
                             FrameKind::FloatingBeam};
  for (int i = 0; i < 16; ++i)
    list.push_back({"random frame scene " + std::to_string(i),
                    fetic::testing::random_frame_scene(rng, kinds[i % 4]),
                    i % 2 == 0 ? MethodKind::FetiC : MethodKind::Mprgp,
                    i % 3 == 0 ? fetic::solver::Preconditioner::Lumped
                               : fetic::solver::Preconditioner::Dirichlet});
  return list;
}

}  // namespace

int main(int argc, char** argv) {
  if (!fetic::solver::mpi_start(&argc, &argv)) return 1;
  const Communicator& world = Communicator::world();
  const std::string scenes_dir = argc > 1 ? argv[1] : "scenes";
  int failures = 0, count = 0;
  for (const Case& c : cases(scenes_dir)) {
    ++count;
    std::string verdict;
    try {
      const fetic::scenes::Scene scene = fetic::scenes::parse_scene(c.text, c.name);
      const fetic::solver::Model model = fetic::solver::build_model(scene);
      const Outcome serial = solve(c, model, Communicator::self());
      const Outcome distributed = solve(c, model, world);
      if (world.root()) verdict = compare(c, model, serial, distributed);
    } catch (const std::exception& error) {
      // Every process meets the same scene errors; a solver error is agreed on by all.
      verdict = std::string("threw: ") + error.what();
    }
    if (world.root() && !verdict.empty()) {
      ++failures;
      std::printf("FAILED %s on %d processes: %s\n", c.name.c_str(), world.size(), verdict.c_str());
    }
  }
  double failed = failures;
  world.broadcast(failed);
  if (world.root())
    std::printf("%d of %d cases agree with the serial solve on %d processes\n", count - failures,
                count, world.size());
  fetic::solver::mpi_finish();
  return failed > 0 ? 1 : 0;
}
