#pragma once
// The names of an enum's values as one table that both directions read, so that a name
// cannot be printed one way and parsed another:
//   constexpr EnumName<ModelKind> kModelNames[] = {{ModelKind::Bar, "bar"}, ...};
//   name_of(kModelNames, ModelKind::Bar) is "bar"; value_named(kModelNames, "bar") is Bar.
// The table's order is the order a list of the names shows them in.

#include <cstddef>
#include <optional>
#include <string_view>

namespace fetic::scenes {

template <typename Enum>
struct EnumName {
  Enum value;
  const char* name;
};

// The name of `value`; "?" for a value the table lacks.
template <typename Enum, std::size_t N>
constexpr const char* name_of(const EnumName<Enum> (&table)[N], Enum value) {
  for (const EnumName<Enum>& entry : table)
    if (entry.value == value) return entry.name;
  return "?";
}

// The value named `name`, if the table has it.
template <typename Enum, std::size_t N>
constexpr std::optional<Enum> value_named(const EnumName<Enum> (&table)[N],
                                          std::string_view name) {
  for (const EnumName<Enum>& entry : table)
    if (name == entry.name) return entry.value;
  return std::nullopt;
}

}  // namespace fetic::scenes
