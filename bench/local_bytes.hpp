#pragma once
// Part `bytes` of fetic-bench-scale: where the memory of a FETI solve goes (bytes per
// unknown by kind), where its set-up time goes, and how close one application of F
// comes to this machine's memory bandwidth (a STREAM-like triad measured in the run).

#include <string>
#include <vector>

#include "scenes/generate_scene.hpp"

namespace fetic::bench {

struct BytesTables {
  std::vector<std::vector<std::string>> memory;  // per scene: bytes per unknown by kind
  std::vector<std::vector<std::string>> setup;   // per scene: set-up seconds by part
  std::vector<std::vector<std::string>> apply;   // per scene: F's bytes, time, bandwidth
  std::vector<std::string> memory_header, setup_header, apply_header;
  double triad = 0.0;  // bytes per second
};

// The best of a few triads a = b + s c over `threads` threads on arrays far larger than
// the caches, in bytes per second (24 bytes moved per element, as STREAM counts).
double triad_bandwidth(int threads);

// Each scene twice: the subdomain factors' entries in double and in single precision
// (SolveOptions::single_factors).
BytesTables local_bytes(const std::vector<scenes::GenerateOptions>& scenes,
                        const std::vector<std::string>& names);

}  // namespace fetic::bench
