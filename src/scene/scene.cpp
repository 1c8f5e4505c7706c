// Scene-wide queries: bounds, area, emitters.
#include "scene/scene.h"

namespace gv {

Aabb Scene::bounds() const {
  Aabb box;
  for (const Patch& p : patches)
    for (const Vec3& v : p.polygon.vertices) box.add(v);
  return box;
}

double Scene::totalArea() const {
  double sum = 0;
  for (const Patch& p : patches) sum += p.polygon.area();
  return sum;
}

size_t Scene::emitterCount() const {
  size_t n = 0;
  for (const Patch& p : patches) n += materials.at(p.material).isEmitter() ? 1 : 0;
  return n;
}

std::vector<double> Scene::emittedPower() const {
  std::vector<double> power;
  power.reserve(patches.size());
  for (const Patch& p : patches)
    power.push_back(p.polygon.area() * materials.at(p.material).emission.maxChannel());
  return power;
}

uint32_t Scene::addMaterial(Material m) {
  materials.push_back(std::move(m));
  return static_cast<uint32_t>(materials.size() - 1);
}

}  // namespace gv
