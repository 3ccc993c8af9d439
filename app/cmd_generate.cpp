// fetic generate: writes a generated scene of any size (TOML) to stdout or a file, e.g.
//   fetic generate --pairs 25 --elements 200,48 --subdomains 10,2 > big.toml

#include <iostream>
#include <memory>
#include <sstream>
#include <string>

#include "app/commands.hpp"
#include "app/exit_codes.hpp"
#include "app/output_file.hpp"
#include "scenes/generate_scene.hpp"
#include "scenes/load_scene.hpp"
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

int run_generate(const GenerateArgs& args) {
  scenes::GenerateOptions options;
  options.model = args.model == "bar" ? scenes::ModelKind::Bar : scenes::ModelKind::Plane;
  options.pairs = args.pairs;
  options.seed = args.seed;
  if (!parse_pair(args.elements, options.elements, options.elements_across) ||
      !parse_pair(args.subdomains, options.subdomains, options.subdomains_across)) {
    std::cerr << "fetic generate: --elements and --subdomains take N or N,M\n";
    return kExitUsage;
  }
  std::string text;
  try {
    const scenes::Scene scene = scenes::generate_scene(options);
    const long long unknowns = scenes::unknowns(scene);
    text = "# " + std::to_string(unknowns) + " unknowns. fetic generate --model " + args.model +
           " --pairs " + std::to_string(args.pairs) + " --elements " + args.elements +
           " --subdomains " + args.subdomains + " --seed " + std::to_string(args.seed) + "\n" +
           scenes::scene_to_toml(scene);
    scenes::parse_scene(text, args.out.empty() ? "<generated>" : args.out);  // stays valid
  } catch (const std::invalid_argument& error) {
    std::cerr << "fetic generate: " << error.what() << '\n';
    return kExitUsage;
  } catch (const scenes::SceneError& error) {
    std::cerr << error.what() << '\n';
    return kExitUsage;
  }
  try {
    write_output(args.out.empty() ? "-" : args.out, text);
  } catch (const OutputError& error) {
    return report_output_error(error);
  }
  return kExitOk;
}

}  // namespace

void register_generate(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<GenerateArgs>();
  CLI::App* command = app.add_subcommand(
      "generate", "Write a generated scene of opposing strut pairs (TOML) to stdout or a file");
  command->add_option("--model", args->model, "bar or plane")
      ->check(CLI::IsMember({"bar", "plane"}))
      ->capture_default_str();
  command->add_option("--pairs", args->pairs, "Pairs of opposing struts")
      ->check(CLI::Range(1, 1000000))
      ->capture_default_str();
  command->add_option("--elements", args->elements, "Elements per strut: along[,across]")
      ->capture_default_str();
  command->add_option("--subdomains", args->subdomains, "Subdomains per strut: along[,across]")
      ->capture_default_str();
  command->add_option("--seed", args->seed, "Seed of the variations")->capture_default_str();
  command->add_option("-o,--out", args->out, "Write to this file instead of stdout (- for stdout)");
  command->callback([args, &exit_code] { exit_code = run_generate(*args); });
}

}  // namespace fetic::app
