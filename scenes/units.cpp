#include "scenes/units.hpp"

#include <array>
#include <cmath>
#include <utility>

namespace fetic::scenes {
namespace {

struct Named {
  const char* name;
  double si;  // the unit in metres or newtons
  bool metric;
};

constexpr std::array<Named, 7> kLengths{{{"m", 1.0, true},
                                         {"mm", 1e-3, true},
                                         {"cm", 1e-2, true},
                                         {"km", 1e3, true},
                                         {"um", 1e-6, true},
                                         {"in", 0.0254, false},
                                         {"ft", 0.3048, false}}};
constexpr std::array<Named, 6> kForces{{{"N", 1.0, true},
                                        {"kN", 1e3, true},
                                        {"MN", 1e6, true},
                                        {"mN", 1e-3, true},
                                        {"lbf", 4.4482216152605, false},
                                        {"kip", 4448.2216152605, false}}};

template <std::size_t N>
const Named* find(const std::array<Named, N>& table, const std::string& name) {
  for (const Named& unit : table)
    if (name == unit.name) return &unit;
  return nullptr;
}

bool metric(const Units& units) {
  const Named* length = find(kLengths, units.length);
  const Named* force = find(kForces, units.force);
  return length && force && length->metric && force->metric;
}

template <std::size_t N>
std::vector<std::string> names_of(const std::array<Named, N>& table) {
  std::vector<std::string> names;
  for (const Named& unit : table)
    names.emplace_back(unit.name);
  return names;
}

// SI prefixes from giga to micro.
constexpr std::array<std::pair<double, const char*>, 6> kPrefixes{
    {{1e9, "G"}, {1e6, "M"}, {1e3, "k"}, {1.0, ""}, {1e-3, "m"}, {1e-6, "µ"}}};

}  // namespace

const std::vector<std::string>& length_unit_names() {
  static const std::vector<std::string> names = names_of(kLengths);
  return names;
}

const std::vector<std::string>& force_unit_names() {
  static const std::vector<std::string> names = names_of(kForces);
  return names;
}

std::optional<double> metres_per(const std::string& length_unit) {
  const Named* unit = find(kLengths, length_unit);
  return unit ? std::optional<double>(unit->si) : std::nullopt;
}

std::optional<double> newtons_per(const std::string& force_unit) {
  const Named* unit = find(kForces, force_unit);
  return unit ? std::optional<double>(unit->si) : std::nullopt;
}

std::string stress_unit(const Units& units) {
  if (metric(units)) {
    const double pascals = *newtons_per(units.force) / std::pow(*metres_per(units.length), 2);
    for (const auto& [factor, prefix] : kPrefixes)
      if (std::abs(pascals / factor - 1.0) < 1e-9) return std::string(prefix) + "Pa";
  }
  if (units.length == "in" && units.force == "lbf") return "psi";
  if (units.length == "in" && units.force == "kip") return "ksi";
  return units.force + "/" + units.length + "²";
}

std::string force_per_length_unit(const Units& units) {
  return units.force + "/" + units.length;
}

DisplayUnit display_unit(Quantity quantity, const Units& units, double largest) {
  // Lengths and distributed loads read best in the units the scene was written in.
  if (quantity == Quantity::Length) return {units.length, 1.0};
  if (quantity == Quantity::ForcePerLength) return {force_per_length_unit(units), 1.0};
  if (quantity == Quantity::Moment) {
    // Engineers read moments in a force unit times the drawing's length unit.
    const DisplayUnit force = display_unit(Quantity::Force, units, largest);
    return {force.name + " " + units.length, force.divisor};
  }
  if (!metric(units)) return {quantity == Quantity::Force ? units.force : stress_unit(units), 1.0};
  const double to_si = quantity == Quantity::Force
                           ? *newtons_per(units.force)
                           : *newtons_per(units.force) / std::pow(*metres_per(units.length), 2);
  const char* base = quantity == Quantity::Force ? "N" : "Pa";
  const double si = std::abs(largest) * to_si;
  if (!(si > 0.0) || !std::isfinite(si)) return {base, 1.0 / to_si};
  for (const auto& [factor, prefix] : kPrefixes)
    if (si >= factor || factor == kPrefixes.back().first)
      return {std::string(prefix) + base, factor / to_si};
  return {base, 1.0 / to_si};
}

}  // namespace fetic::scenes
