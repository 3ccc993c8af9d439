#pragma once
// Generated test scenes of any size: `pairs` pairs of opposing struts in the spirit of
// the thesis' problem. Left struts are clamped at their left ends; right struts are
// clamped at their right ends and pushed toward the left ones; gaps, loads and
// stiffnesses vary from pair to pair (deterministically, from a seed). In the plane
// model the left struts are also bent across their axis, so that their end faces close
// over only part of the height. In the frame model a "pair" is two portal frames (two
// clamped columns and a beam, rigid corners) side by side whose facing corners are a
// gap apart; wind on the outer columns sways them toward each other.

#include <cstdint>
#include <functional>

#include "scenes/scene.hpp"

namespace fetic::scenes {

struct GenerateOptions {
  ModelKind model = ModelKind::Plane;
  int pairs = 10;
  int elements = 32;          // along each strut
  int elements_across = 8;    // plane model
  int subdomains = 4;         // along each strut
  int subdomains_across = 1;  // plane model
  std::uint32_t seed = 1;
  // Asked every 1024 pairs: when it returns true, the generation stops early and returns
  // the pairs made so far (the caller, interrupted, discards them). ({}: designated
  // initializers may leave it out.)
  std::function<bool()> stop{};
};

// Unknowns of the scene generate_scene() would make, computed without making it.
long long generated_unknowns(const GenerateOptions& options);

// Throws std::invalid_argument for options that would give an invalid scene.
Scene generate_scene(const GenerateOptions& options);

}  // namespace fetic::scenes
