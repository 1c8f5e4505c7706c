// Solver-vs-photon statistics per patch channel (see photon_comparison.h).
#include "radiosity/photon_comparison.h"

#include <cmath>

#include "util/check.h"

namespace gv {

PhotonComparison comparePhotons(const Scene& scene, const std::vector<Rgb>& solver,
                                const PhotonResult& reference, double sigmas, double allowance) {
  CHECK_MSG(reference.radiosity.size() >= scene.patches.size() &&
                reference.standardError.size() >= scene.patches.size(),
            "photon reference of {} patches for a scene of {}", reference.radiosity.size(),
            scene.patches.size());
  PhotonComparison c;
  double sumSq = 0, areaSum = 0;
  for (size_t p = 0; p < scene.patches.size() && p < solver.size(); ++p) {
    const double area = scene.patches[p].polygon.area();
    const double s[3] = {solver[p].r, solver[p].g, solver[p].b};
    const Rgb& mr = reference.radiosity[p];
    const Rgb& er = reference.standardError[p];
    const double m[3] = {mr.r, mr.g, mr.b};
    const double e[3] = {er.r, er.g, er.b};
    for (int ch = 0; ch < 3; ++ch) {
      if (!(m[ch] > 0) || e[ch] > kMeaningfulPhotonNoise * m[ch]) continue;
      const double rel = (s[ch] - m[ch]) / m[ch];
      ++c.compared;
      sumSq += rel * rel;
      c.meanSigned += rel;
      c.areaWeightedSigned += area * rel;
      areaSum += area;
      if (std::abs(rel) > c.maxRelative) {
        c.maxRelative = std::abs(rel);
        c.worstPatch = p;
        c.worstChannel = ch;
      }
      if (std::abs(s[ch] - m[ch]) > sigmas * e[ch] + allowance * m[ch]) ++c.failures;
    }
  }
  if (c.compared > 0) {
    c.rmsRelative = std::sqrt(sumSq / static_cast<double>(c.compared));
    c.meanSigned /= static_cast<double>(c.compared);
    c.areaWeightedSigned /= areaSum;
  }
  return c;
}

}  // namespace gv
