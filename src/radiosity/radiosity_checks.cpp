// The checks and the hash of radiosity_checks.h.
#include "radiosity/radiosity_checks.h"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <utility>

#include "util/fnv_hash.h"

namespace gv {

std::optional<std::string> checkRadiosity(const Scene& scene, const RadiosityResult& r,
                                          const RadiosityCheckOptions& options) {
  if (r.patchRadiosity.size() != scene.patches.size()) return "radiosity per patch missing";
  for (size_t k = 0; k < scene.patches.size(); ++k) {
    const Rgb& b = r.patchRadiosity[k];
    const Rgb& e = scene.materials.at(scene.patches[k].material).emission;
    for (auto [value, emitted] : {std::pair{b.r, e.r}, {b.g, e.g}, {b.b, e.b}})
      if (!std::isfinite(value) || value < emitted * (1 - 1e-9))
        return fmt::format("patch {} radiosity {} below its emission {}", k, value, emitted);
  }
  if (options.converged && !r.stats.converged) return "radiosity did not converge";
  if (options.energyBound) {
    double emitted = 0, out = 0, maxRho = 0;
    for (size_t p = 0; p < scene.patches.size(); ++p) {
      const Material& m = scene.materials[scene.patches[p].material];
      const double a = scene.patches[p].polygon.area();
      const Rgb& b = r.patchRadiosity[p];
      emitted += a * (m.emission.r + m.emission.g + m.emission.b);
      out += a * (b.r + b.g + b.b);
      maxRho = std::max({maxRho, m.reflectance.r, m.reflectance.g, m.reflectance.b});
    }
    if (!(out >= emitted && out <= emitted / (1 - maxRho)))
      return fmt::format("energy bound: sum A*B {} outside [{}, {}]", out, emitted,
                         emitted / (1 - maxRho));
  }
  return std::nullopt;
}

uint64_t radiosityHash(const RadiosityResult& r) {
  Fnv1a h;
  for (const Rgb& c : r.patchRadiosity) h.text(fmt::format("{:.5e} {:.5e} {:.5e};", c.r, c.g, c.b));
  return h.value();
}

}  // namespace gv
