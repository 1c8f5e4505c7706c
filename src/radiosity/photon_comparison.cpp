// Solver-vs-photon statistics per surface channel, leaks, regions and the L2 of B − Ke (see
// photon_comparison.h).
#include "radiosity/photon_comparison.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>

#include "scene/coincident_patches.h"
#include "util/check.h"

namespace gv {
namespace {

using Channels = std::array<double, 3>;

Channels channelsOf(const Rgb& c) {
  return {c.r, c.g, c.b};
}

/// A patch, or a group of coincident patches taken as one (scene/coincident_patches.h).
struct Surface {
  std::vector<uint32_t> patches;
  double area = 0;         ///< the members' areas summed
  double surfaceArea = 0;  ///< one member's (their mean): what the photons of the group fell on
  Channels solver{}, emission{};  ///< area-weighted means of the members
  Channels photonReflected{};     ///< photon power over the group / surfaceArea
  Channels photonError{};         ///< its standard error (members' taken as independent)
  Channels photonRaw{};           ///< Σ A (B − Ke) of the photons, to tell "no photon" apart
  /// The solution's irradiance, (B − Ke) / ρ area-weighted over the members with ρ > 0, and
  /// the area of those members (0: the channel reflects nothing here).
  Channels irradiance{}, reflectingArea{};

  double solverReflected(int ch) const { return solver[ch] - emission[ch]; }
  double photonB(int ch) const { return emission[ch] + photonReflected[ch]; }
  bool noPhoton(int ch) const { return !(photonRaw[ch] > 0) && !(photonError[ch] > 0); }
};

std::vector<Surface> makeSurfaces(const Scene& scene, const std::vector<Rgb>& solver,
                                  const PhotonResult& reference, size_t n) {
  const std::vector<uint32_t> group = coincidentPatchGroups(scene);
  std::vector<Surface> surfaces;
  std::vector<size_t> surfaceOf(n);
  for (size_t p = 0; p < n; ++p) {
    if (group[p] == p) {
      surfaceOf[p] = surfaces.size();
      surfaces.emplace_back();
    } else {
      surfaceOf[p] = surfaceOf[group[p]];
    }
    Surface& f = surfaces[surfaceOf[p]];
    f.patches.push_back(static_cast<uint32_t>(p));
    const double a = scene.patches[p].polygon.area();
    const Material& m = scene.materials[scene.patches[p].material];
    const Channels s = channelsOf(solver[p]), ke = channelsOf(m.emission),
                   kd = channelsOf(m.reflectance), b = channelsOf(reference.radiosity[p]),
                   e = channelsOf(reference.standardError[p]);
    f.area += a;
    for (int ch = 0; ch < 3; ++ch) {
      f.solver[ch] += a * s[ch];
      f.emission[ch] += a * ke[ch];
      f.photonRaw[ch] += a * (b[ch] - ke[ch]);
      f.photonError[ch] += a * a * e[ch] * e[ch];
      if (kd[ch] > 0) {
        f.irradiance[ch] += a * (s[ch] - ke[ch]) / kd[ch];
        f.reflectingArea[ch] += a;
      }
    }
  }
  for (Surface& f : surfaces) {
    if (!(f.area > 0)) continue;
    f.surfaceArea = f.area / static_cast<double>(f.patches.size());
    for (int ch = 0; ch < 3; ++ch) {
      f.solver[ch] /= f.area;
      f.emission[ch] /= f.area;
      f.photonReflected[ch] = f.photonRaw[ch] / f.surfaceArea;
      f.photonError[ch] = std::sqrt(f.photonError[ch]) / f.surfaceArea;
      if (f.reflectingArea[ch] > 0) f.irradiance[ch] /= f.reflectingArea[ch];
    }
  }
  return surfaces;
}

/// The per-channel figures of the compared surface channels (B as written).
void compareChannel(PhotonComparison& c, const Surface& f, int ch, double sigmas, double allowance,
                    double& sumSq, double& areaSum) {
  const double s = f.solver[ch], m = f.photonB(ch), e = f.photonError[ch];
  const double rel = (s - m) / m;
  ++c.compared;
  sumSq += rel * rel;
  c.meanSigned += rel;
  c.areaWeightedSigned += f.area * rel;
  areaSum += f.area;
  if (std::abs(rel) > c.maxRelative) {
    c.maxRelative = std::abs(rel);
    c.worstPatch = f.patches.front();
    c.worstChannel = ch;
  }
  if (std::abs(s - m) > sigmas * e + allowance * m) ++c.failures;
}

/// A surface channel no photon reached: a leak, too dim to tell, or unlit in the solution too.
void countZeroPhoton(PhotonComparison& c, const Surface& f, int ch, double photonPower,
                     std::vector<PhotonLeak>& leaks, double& leakedPower) {
  ++c.channels.zeroPhoton;
  const double b = f.solverReflected(ch);
  if (!(f.reflectingArea[ch] > 0) || !(b > 0) || !(f.irradiance[ch] > 0)) {
    ++c.channels.unlit;
    return;
  }
  // Reflected power / (ρ · photon power): the hits the tracer would have tallied.
  const double expected = photonPower > 0 ? f.irradiance[ch] * f.surfaceArea / photonPower : 0.0;
  if (expected < kLeakExpectedHits) {
    ++c.channels.tooDim;
    return;
  }
  ++c.channels.leaks;
  leaks.push_back({f.patches.front(), ch, expected, b});
  leakedPower += b * f.surfaceArea;
}

struct RegionSums {
  Channels solver{}, photons{}, variance{};
  size_t patches = 0;
};

void compareRegions(PhotonComparison& c, const Scene& scene, const std::vector<Surface>& surfaces,
                    double size) {
  CHECK_MSG(size > 0, "region size {}", size);
  c.regionSize = size;
  std::map<std::array<int64_t, 3>, RegionSums> regions;  // ordered: ties resolve the same way
  Channels totalSolver{}, totalPhotons{};
  for (const Surface& f : surfaces) {
    if (!(f.area > 0)) continue;
    const Vec3 at = scene.patches[f.patches.front()].polygon.centroid();
    const std::array<int64_t, 3> key{static_cast<int64_t>(std::floor(at.x / size)),
                                     static_cast<int64_t>(std::floor(at.y / size)),
                                     static_cast<int64_t>(std::floor(at.z / size))};
    RegionSums& r = regions[key];
    r.patches += f.patches.size();
    for (int ch = 0; ch < 3; ++ch) {
      const double solver = f.solverReflected(ch) * f.surfaceArea;
      const double photons = f.photonReflected[ch] * f.surfaceArea;
      const double error = f.photonError[ch] * f.surfaceArea;
      r.solver[ch] += solver;
      r.photons[ch] += photons;
      r.variance[ch] += error * error;
      totalSolver[ch] += solver;
      totalPhotons[ch] += photons;
    }
  }
  for (const auto& [key, r] : regions) {
    for (int ch = 0; ch < 3; ++ch) {
      ++c.regionChannels;
      const double share = std::max(totalSolver[ch] > 0 ? r.solver[ch] / totalSolver[ch] : 0.0,
                                    totalPhotons[ch] > 0 ? r.photons[ch] / totalPhotons[ch] : 0.0);
      if (!(share >= kMinRegionShare)) {
        ++c.regionsSmall;
        continue;
      }
      if (!(r.photons[ch] > 0) ||
          std::sqrt(r.variance[ch]) > kMeaningfulRegionNoise * r.photons[ch]) {
        ++c.regionsNoisy;
        continue;
      }
      ++c.regionsCompared;
      const double rel = (r.solver[ch] - r.photons[ch]) / r.photons[ch];
      if (!c.worstRegion || std::abs(rel) > std::abs(c.worstRegion->relative)) {
        const Vec3 low{static_cast<double>(key[0]) * size, static_cast<double>(key[1]) * size,
                       static_cast<double>(key[2]) * size};
        c.worstRegion = PhotonRegion{low, ch, r.solver[ch], r.photons[ch], rel, r.patches};
      }
    }
  }
}

}  // namespace

PhotonComparison comparePhotons(const Scene& scene, const std::vector<Rgb>& solver,
                                const PhotonResult& reference, double sigmas, double allowance,
                                double regionSize) {
  CHECK_MSG(reference.radiosity.size() >= scene.patches.size() &&
                reference.standardError.size() >= scene.patches.size(),
            "photon reference of {} patches for a scene of {}", reference.radiosity.size(),
            scene.patches.size());
  const size_t n = std::min(scene.patches.size(), solver.size());
  const std::vector<Surface> surfaces = makeSurfaces(scene, solver, reference, n);
  const Channels photonPower = channelsOf(reference.photonPower);
  PhotonComparison c;
  c.surfaces = surfaces.size();
  double sumSq = 0, areaSum = 0, leakedPower = 0, reflectedPower = 0;
  std::vector<PhotonLeak> leaks;
  for (const Surface& f : surfaces) {
    if (f.patches.size() > 1) {
      ++c.twinGroups;
      c.twinPatches += f.patches.size();
    }
    const size_t leaksBefore = leaks.size();
    for (int ch = 0; ch < 3; ++ch) {
      ++c.channels.total;
      reflectedPower += std::max(0.0, f.solverReflected(ch)) * f.surfaceArea;
      if (f.noPhoton(ch)) {
        countZeroPhoton(c, f, ch, photonPower[ch], leaks, leakedPower);
      } else if (f.photonB(ch) > 0 && f.photonError[ch] <= kMeaningfulPhotonNoise * f.photonB(ch)) {
        compareChannel(c, f, ch, sigmas, allowance, sumSq, areaSum);
      } else {
        ++c.channels.noisy;
      }
    }
    if (leaks.size() > leaksBefore) {
      ++c.leakSurfaces;
      c.leakPatches += f.patches.size();
    }
  }
  c.channels.compared = c.compared;
  if (c.compared > 0) {
    c.rmsRelative = std::sqrt(sumSq / static_cast<double>(c.compared));
    c.meanSigned /= static_cast<double>(c.compared);
    c.areaWeightedSigned /= areaSum;
  }
  if (reflectedPower > 0) c.leakedPowerShare = leakedPower / reflectedPower;
  const size_t shown = std::min(kReportedLeaks, leaks.size());
  std::partial_sort(leaks.begin(), leaks.begin() + static_cast<ptrdiff_t>(shown), leaks.end(),
                    [](const PhotonLeak& a, const PhotonLeak& b) {
                      return a.expectedHits > b.expectedHits ||
                             (a.expectedHits == b.expectedHits && a.patch < b.patch);
                    });
  c.worstLeaks.assign(leaks.begin(), leaks.begin() + static_cast<ptrdiff_t>(shown));

  // The headline figure: every patch, each held to its surface's photon estimate.
  // Beside it, what the photons' own noise contributes (the expected Σ A (p − p̄)² of the
  // estimates, from their standard errors).
  double num = 0, den = 0, noise = 0;
  for (const Surface& f : surfaces)
    for (const uint32_t p : f.patches) {
      const double a = scene.patches[p].polygon.area();
      const Channels s = channelsOf(solver[p]);
      const Channels ke = channelsOf(scene.materials[scene.patches[p].material].emission);
      for (int ch = 0; ch < 3; ++ch) {
        const double d = s[ch] - ke[ch] - f.photonReflected[ch];
        num += a * d * d;
        den += a * f.photonReflected[ch] * f.photonReflected[ch];
        noise += a * f.photonError[ch] * f.photonError[ch];
      }
    }
  const auto ratio = [&](double x) {
    return den > 0 ? std::sqrt(x / den) : (x > 0 ? std::numeric_limits<double>::infinity() : 0.0);
  };
  c.l2Reflected = ratio(num);
  c.l2PhotonNoise = ratio(noise);

  compareRegions(c, scene, surfaces, regionSize);
  return c;
}

}  // namespace gv
