#include "scenes/scene.hpp"

#include "scenes/enum_names.hpp"

namespace fetic::scenes {

namespace {

constexpr EnumName<ModelKind> kModelNames[] = {
    {ModelKind::Bar, "bar"}, {ModelKind::Plane, "plane"}, {ModelKind::Frame, "frame"}};

}  // namespace

const char* to_string(ModelKind model) {
  return name_of(kModelNames, model);
}

std::optional<ModelKind> parse_model(std::string_view name) {
  return value_named(kModelNames, name);
}

const char* to_string(JointKind kind) {
  return kind == JointKind::Rigid ? "rigid" : "pinned";
}

const char* to_string(StrutEnd end) {
  return end == StrutEnd::From ? "from" : "to";
}

std::string end_label(const Scene& scene, EndRef ref) {
  const std::string& name = scene.struts.at(ref.strut).name;
  if (ref.node >= 0) return name + "@" + std::to_string(ref.node);
  return name + "." + to_string(ref.end);
}

int node_index(const Scene& scene, EndRef ref) {
  if (ref.node >= 0) return ref.node;
  return ref.end == StrutEnd::From ? 0 : scene.struts.at(ref.strut).elements;
}

int nodes_across(const Scene& scene, const Strut& strut) {
  return scene.model == ModelKind::Plane ? strut.elements_across + 1 : 1;
}

long long unknowns(const Scene& scene) {
  long long total = 0;
  const long long per_node =
      scene.model == ModelKind::Bar ? 1 : (scene.model == ModelKind::Plane ? 2 : 3);
  for (const Strut& strut : scene.struts)
    total += per_node * (static_cast<long long>(strut.elements) + 1) * nodes_across(scene, strut);
  return total;
}

}  // namespace fetic::scenes
