#include "scenes/scene.hpp"

namespace fetic::scenes {

const char* to_string(ModelKind model) {
  return model == ModelKind::Bar ? "bar" : "plane";
}

const char* to_string(StrutEnd end) {
  return end == StrutEnd::From ? "from" : "to";
}

std::string end_label(const Scene& scene, EndRef ref) {
  return scene.struts.at(ref.strut).name + "." + to_string(ref.end);
}

int nodes_across(const Scene& scene, const Strut& strut) {
  return scene.model == ModelKind::Bar ? 1 : strut.elements_across + 1;
}

long long unknowns(const Scene& scene) {
  long long total = 0;
  const long long per_node = scene.model == ModelKind::Bar ? 1 : 2;
  for (const Strut& strut : scene.struts)
    total += per_node * (static_cast<long long>(strut.elements) + 1) * nodes_across(scene, strut);
  return total;
}

}  // namespace fetic::scenes
