// fetic generate: writes a generated scene of any size (TOML) to stdout or a file, e.g.
//   fetic generate --pairs 25 --elements 200,48 --subdomains 10,2 > big.toml

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>

#include "app/commands.hpp"
#include "app/exit_codes.hpp"
#include "app/interrupt.hpp"
#include "app/memory_estimate.hpp"
#include "app/out_of_memory.hpp"
#include "app/output_file.hpp"
#include "app/output_options.hpp"
#include "scenes/generate_scene.hpp"
#include "scenes/load_scene.hpp"
#include "scenes/scene_text.hpp"
#include "scenes/write_scene.hpp"

namespace fetic::app {
namespace {

struct GenerateArgs {
  std::string model = "plane";
  int pairs = 10;
  std::string elements = "32,8";
  std::string subdomains = "4,1";
  unsigned seed = 1;
  std::string out;
};

// "NX,NY" or "NX" -> (NX, NY or fallback).
bool parse_pair(const std::string& text, int& first, int& second) {
  std::istringstream in(text);
  char comma = 0;
  if (!(in >> first)) return false;
  if (in >> comma) {
    if (comma != ',' || !(in >> second)) return false;
  }
  in >> std::ws;
  return in.eof();
}

// The header line that says how the scene was made.
std::string header(const GenerateArgs& args, long long unknowns) {
  return "# " + std::to_string(unknowns) + " unknowns. fetic generate --model " + args.model +
         " --pairs " + std::to_string(args.pairs) + " --elements " + args.elements +
         " --subdomains " + args.subdomains + " --seed " + std::to_string(args.seed) + "\n";
}

int interrupted_status() {
  std::cerr << "fetic generate: interrupted by " << interrupt_name() << "; no scene written\n";
  return kExitInterrupted;
}

// The counts themselves, named by option and value: what generate_scene() requires.
std::string count_problem(const GenerateArgs& args, const scenes::GenerateOptions& options) {
  const bool plane = options.model == scenes::ModelKind::Plane;
  if (options.elements < 1 || (plane && options.elements_across < 1))
    return "--elements " + args.elements + ": the counts must be whole numbers of at least 1";
  if (options.subdomains < 1 || (plane && options.subdomains_across < 1))
    return "--subdomains " + args.subdomains + ": the counts must be whole numbers of at least 1";
  if (options.subdomains > options.elements)
    return "--subdomains " + args.subdomains + ": " + std::to_string(options.subdomains) +
           " subdomains along a strut of " + std::to_string(options.elements) +
           " elements; each subdomain needs an element";
  if (plane && options.subdomains_across > options.elements_across)
    return "--subdomains " + args.subdomains + ": " + std::to_string(options.subdomains_across) +
           " subdomains across a strut " + std::to_string(options.elements_across) +
           " elements wide; each subdomain needs an element";
  return "";
}

// The limits a scene file must keep, checked before anything is made: the unknowns from
// the options, the size of the text from a few pairs made for it.
std::string limit_problem(const GenerateArgs& args, const scenes::GenerateOptions& options) {
  // In floating point: the product of the counts overflows 64-bit integers.
  const bool plane = options.model == scenes::ModelKind::Plane;
  const double unknowns = 2.0 * options.pairs * (options.elements + 1.0) *
                          (plane ? 2.0 * (options.elements_across + 1.0) : 1.0);
  if (unknowns > static_cast<double>(scenes::kMaxUnknowns)) {
    char text[200];
    std::snprintf(text, sizeof text,
                  "the scene would have %.0f unknowns, more than the limit of %lld a scene may "
                  "have; use fewer pairs or elements",
                  unknowns, static_cast<long long>(scenes::kMaxUnknowns));
    return text;
  }
  scenes::GenerateOptions sample = options;
  sample.pairs = std::min(options.pairs, 16);
  const double per_pair =
      static_cast<double>(scenes::scene_to_toml(scenes::generate_scene(sample)).size()) /
      sample.pairs;
  // Names and numbers grow by a few digits over the pairs: 10% on top.
  const double bytes = 1.1 * per_pair * options.pairs + static_cast<double>(header(args, 0).size());
  // The format's limit first: it refuses the same options on every machine.
  if (bytes > static_cast<double>(scenes::kMaxSceneFileBytes)) {
    char text[160];
    std::snprintf(text, sizeof text,
                  "the scene would have about %.0f MiB of TOML, more than the %.0f MiB a scene "
                  "file may have (about %.0f pairs of this kind fit)",
                  bytes / (1 << 20), static_cast<double>(scenes::kMaxSceneFileBytes) / (1 << 20),
                  std::floor(static_cast<double>(scenes::kMaxSceneFileBytes) / (1.1 * per_pair)));
    return text;
  }
  if (const auto available = available_memory();
      available && memory_check_enabled() &&
      estimate_parse_memory(bytes) + bytes > available->bytes)
    return "not enough memory: making and checking a scene of about " + memory_text(bytes) +
           " needs about " + memory_text(estimate_parse_memory(bytes) + bytes) + ", and " +
           memory_text(available->bytes) + " is available (" + available->limited_by + ")";
  return "";
}

int run_generate(const GenerateArgs& args) {
  scenes::GenerateOptions options;
  options.model = args.model == "bar"     ? scenes::ModelKind::Bar
                  : args.model == "frame" ? scenes::ModelKind::Frame
                                          : scenes::ModelKind::Plane;
  options.pairs = args.pairs;
  options.seed = args.seed;
  options.stop = [] { return interrupted(); };
  if (!parse_pair(args.elements, options.elements, options.elements_across) ||
      !parse_pair(args.subdomains, options.subdomains, options.subdomains_across)) {
    std::cerr << "fetic generate: --elements and --subdomains take N or N,M (whole numbers), got "
              << "--elements " << args.elements << " --subdomains " << args.subdomains << '\n';
    return kExitUsage;
  }
  std::string text;
  try {
    Activity generating("generating the scene");
    if (const std::string problem = count_problem(args, options); !problem.empty()) {
      std::cerr << "fetic generate: " << problem << '\n';
      return kExitUsage;
    }
    if (const std::string problem = limit_problem(args, options); !problem.empty()) {
      std::cerr << "fetic generate: " << problem << '\n';
      return problem.starts_with("not enough memory") ? kExitOutOfMemory : kExitUsage;
    }
    const scenes::Scene scene = scenes::generate_scene(options);
    if (interrupted()) return interrupted_status();
    text = header(args, scenes::unknowns(scene)) + scenes::scene_to_toml(scene);
    if (interrupted()) return interrupted_status();
    scenes::parse_scene(text, args.out.empty() ? "<generated>" : args.out);  // stays valid
    if (interrupted()) return interrupted_status();
  } catch (const std::invalid_argument& error) {
    std::cerr << "fetic generate: " << error.what() << '\n';
    return kExitUsage;
  } catch (const scenes::SceneError& error) {
    std::cerr << error.what() << '\n';
    return kExitUsage;
  }
  return exit_status_of_writing([&] { write_output(args.out.empty() ? "-" : args.out, text); });
}

}  // namespace

void register_generate(CLI::App& app, int& exit_code) {
  const auto [command, args] = add_command(
      app, "generate", "Write a generated scene of opposing strut pairs (TOML) to stdout or a file",
      exit_code, run_generate);
  command
      ->add_option("--model", args->model,
                   "bar, plane or frame (frame: pairs of facing portal frames)")
      ->check(CLI::IsMember({"bar", "plane", "frame"}))
      ->capture_default_str();
  command->add_option("--pairs", args->pairs, "Pairs of opposing struts")
      ->check(CLI::Range(1, 1000000))
      ->capture_default_str();
  command->add_option("--elements", args->elements, "Elements per strut: along[,across]")
      ->capture_default_str();
  command->add_option("--subdomains", args->subdomains, "Subdomains per strut: along[,across]")
      ->capture_default_str();
  command->add_option("--seed", args->seed, "Seed of the variations")->capture_default_str();
  command->add_option("-o,--out", args->out, "Write to this file instead of stdout (- for stdout)")
      ->check(output_name());
}

}  // namespace fetic::app
