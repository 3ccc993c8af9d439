#pragma once
// The units a scene is written in (optional `[units]` table, docs/SCENES.md): a length
// and a force unit; stresses, distributed loads and the rest follow from them. The solver
// does not care (any consistent system works); legends, summaries, warnings and result
// files name them. Default SI: m and N.

#include <optional>
#include <string>
#include <vector>

namespace fetic::scenes {

struct Units {
  std::string length = "m";
  std::string force = "N";
  bool operator==(const Units&) const = default;
};

// The names `[units]` accepts, and what one of them is in SI (metres, newtons); nullopt
// for a name it does not know.
const std::vector<std::string>& length_unit_names();
const std::vector<std::string>& force_unit_names();
std::optional<double> metres_per(const std::string& length_unit);
std::optional<double> newtons_per(const std::string& force_unit);

// The unit of a stress (force per area) and of a distributed load (force per length) in
// these units: "Pa", "MPa" (N/mm²), "psi" (lbf/in²), "ksi", else e.g. "kN/cm²"; "N/m",
// "kN/m", "lbf/in".
std::string stress_unit(const Units& units);
std::string force_per_length_unit(const Units& units);

// A quantity's unit and how to print a value of it: when the scene's units are metric,
// values are shown in the SI unit with the prefix that makes `largest` read between 1 and
// 1000 (420 in N/mm² reads "420 MPa"); otherwise in the scene's own unit. A Moment (force
// times length) keeps the scene's length unit and prefixes its force like Force does:
// "kN m", "N mm", "kN mm"; "lbf in" in imperial units.
enum class Quantity { Length, Force, Stress, ForcePerLength, Moment };
struct DisplayUnit {
  std::string name;      // e.g. "MPa"
  double divisor = 1.0;  // value in the scene's units / divisor = number shown
};
DisplayUnit display_unit(Quantity quantity, const Units& units, double largest);

}  // namespace fetic::scenes
