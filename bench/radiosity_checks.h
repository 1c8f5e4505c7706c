// What every radiosity benchmark checks before it reports a time, and the hash it prints so that
// a speed-up which changes the answer shows: convergence, lights at least their emission, and the
// energy bound Σ A B <= Σ A E / (1 − max ρ).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>

#include "radiosity/hierarchical_radiosity.h"

namespace gv::bench {

inline void checkRadiosity(const Scene& scene, const RadiosityResult& r) {
  if (!r.stats.converged) throw std::runtime_error("radiosity did not converge");
  double emitted = 0, out = 0, maxRho = 0;
  for (size_t p = 0; p < scene.patches.size(); ++p) {
    const Material& m = scene.materials[scene.patches[p].material];
    const double a = scene.patches[p].polygon.area();
    const Rgb& b = r.patchRadiosity[p];
    if (b.r < m.emission.r || b.g < m.emission.g || b.b < m.emission.b)
      throw std::runtime_error("radiosity below emission");
    emitted += a * (m.emission.r + m.emission.g + m.emission.b);
    out += a * (b.r + b.g + b.b);
    maxRho = std::max({maxRho, m.reflectance.r, m.reflectance.g, m.reflectance.b});
  }
  if (!(out >= emitted && out <= emitted / (1 - maxRho))) throw std::runtime_error("energy bound");
}

/// FNV-1a over the per-patch radiosity rounded to 1e-6.
inline uint64_t radiosityHash(const RadiosityResult& r) {
  uint64_t h = 1469598103934665603ull;
  for (const Rgb& c : r.patchRadiosity)
    for (double v : {c.r, c.g, c.b})
      h = (h ^ static_cast<uint64_t>(std::llround(v * 1e6))) * 1099511628211ull;
  return h;
}

}  // namespace gv::bench
