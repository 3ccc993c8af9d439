#include "app/json_layout.hpp"

#include <utility>

namespace fetic::app {
namespace {

void reorder(nlohmann::ordered_json& node) {
  if (node.is_array()) {
    for (auto& item : node)
      if (item.is_structured()) reorder(item);
    return;
  }
  if (!node.is_object()) return;
  nlohmann::ordered_json result = nlohmann::ordered_json::object();
  for (auto& [key, value] : node.items())
    if (!value.is_structured()) result[key] = std::move(value);
  for (auto& [key, value] : node.items())
    if (value.is_structured()) {
      reorder(value);
      result[key] = std::move(value);
    }
  node = std::move(result);
}

}  // namespace

nlohmann::ordered_json scalars_first(nlohmann::ordered_json document) {
  reorder(document);
  return document;
}

}  // namespace fetic::app
