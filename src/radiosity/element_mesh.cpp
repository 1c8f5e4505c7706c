// Leaf elements as an indexed mesh with smooth per-vertex radiosity.
#include "radiosity/element_mesh.h"

#include <bit>
#include <map>
#include <tuple>

namespace gv {

ElementMesh buildElementMesh(const RadiosityResult& result) {
  const ElementTree& tree = result.elements;
  using Key = std::tuple<uint32_t, uint64_t, uint64_t, uint64_t>;  // patch, exact position
  std::map<Key, uint32_t> index;
  std::vector<double> weight;
  ElementMesh mesh;
  for (uint32_t e = 0; e < tree.size(); ++e) {
    const Element& el = tree[e];
    if (!el.isLeaf()) continue;
    std::vector<uint32_t> face;
    const Rgb& b = result.elementRadiosity[e];
    for (const Vec3& v : el.polygon.vertices) {
      const Key key{el.patch, std::bit_cast<uint64_t>(v.x), std::bit_cast<uint64_t>(v.y),
                    std::bit_cast<uint64_t>(v.z)};
      auto [it, fresh] = index.try_emplace(key, static_cast<uint32_t>(mesh.positions.size()));
      if (fresh) {
        mesh.positions.push_back(v);
        mesh.vertexRadiosity.push_back({});
        weight.push_back(0);
      }
      Rgb& sum = mesh.vertexRadiosity[it->second];
      sum = {sum.r + el.area * b.r, sum.g + el.area * b.g, sum.b + el.area * b.b};
      weight[it->second] += el.area;
      face.push_back(it->second);
    }
    mesh.faces.push_back(std::move(face));
    mesh.faceElement.push_back(e);
  }
  for (size_t v = 0; v < mesh.positions.size(); ++v) {
    Rgb& c = mesh.vertexRadiosity[v];
    if (weight[v] > 0) c = {c.r / weight[v], c.g / weight[v], c.b / weight[v]};
  }
  return mesh;
}

}  // namespace gv
