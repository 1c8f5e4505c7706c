// Light tracing with per-patch power tallies: the independent Monte Carlo reference of the
// radiosity checks (HSA91's solutions against a method with no form factors and no meshing).
#include "radiosity/photon_reference.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "radiosity/polygon_sampling.h"
#include "radiosity/ray_visibility.h"

namespace gv {
namespace {

double channelSum(const Rgb& c) {
  return c.r + c.g + c.b;
}

struct Batch {
  std::vector<Rgb> reflected;  ///< power reflected per patch
  uint64_t rays = 0;
};

}  // namespace

PhotonResult photonReference(const Scene& scene, const EmbreeScene& rays,
                             const PhotonOptions& options) {
  if (options.batches < 2) throw std::invalid_argument("photon reference needs >= 2 batches");
  const size_t n = scene.patches.size();
  // Emitters and the cumulative distribution of their emitted power (sum of channels).
  std::vector<uint32_t> emitters;
  std::vector<double> cdf{0.0};
  std::vector<double> areas(n);
  for (size_t k = 0; k < n; ++k) {
    areas[k] = scene.patches[k].polygon.area();
    const Rgb& e = scene.materials.at(scene.patches[k].material).emission;
    if (channelSum(e) > 0 && areas[k] > 0) {
      emitters.push_back(static_cast<uint32_t>(k));
      cdf.push_back(cdf.back() + areas[k] * channelSum(e));
    }
  }
  PhotonResult result;
  result.radiosity.resize(n);
  result.standardError.resize(n);
  for (size_t k = 0; k < n; ++k)
    result.radiosity[k] = scene.materials[scene.patches[k].material].emission;
  if (emitters.empty()) return result;
  const double totalWeight = cdf.back();

  const double offset = kRayEndOffset * scene.bounds().diagonal();
  const auto batches = static_cast<size_t>(options.batches);
  const uint64_t perBatch = std::max<uint64_t>(1, options.photons / batches);
  std::vector<Batch> out(batches);
  tbb::parallel_for(size_t{0}, batches, [&](size_t bi) {
    Batch& batch = out[bi];
    batch.reflected.assign(n, Rgb{});
    SplitMix64 rng(mixSeed(options.seed, 0x9407, bi));
    for (uint64_t i = 0; i < perBatch; ++i) {
      const double pick = rng.uniform() * totalWeight;
      size_t k = static_cast<size_t>(std::upper_bound(cdf.begin(), cdf.end(), pick) - cdf.begin());
      k = std::clamp<size_t>(k, 1, emitters.size()) - 1;
      uint32_t patch = emitters[k];
      const Rgb& e = scene.materials[scene.patches[patch].material].emission;
      // Power A E / (probability of this emitter) / photons: unbiased for the emitted power.
      const double scale = totalWeight / channelSum(e) / static_cast<double>(perBatch);
      Rgb power{e.r * scale, e.g * scale, e.b * scale};
      Vec3 origin = uniformPoint(scene.patches[patch].polygon.vertices, rng);
      for (int bounce = 0; bounce < options.maxBounces; ++bounce) {
        const Vec3 dir = cosineDirection(scene.patches[patch].polygon.plane.normal, rng);
        ++batch.rays;
        // Start a little along (see kRayEndOffset): coplanar neighbours of the origin patch.
        const Vec3 start = origin + dir * offset;
        std::optional<RayHit> hit = rays.firstHit(start, dir, 1e300, patch);
        if (!hit) break;
        if (dot(dir, scene.patches[hit->patch].polygon.plane.normal) >= 0) {
          // A back: but a front-facing patch may lie in the same place (two faces back to
          // back); single precision picks either. Prefer a front within the offset.
          const std::optional<RayHit> other =
              rays.firstHit(start, dir, hit->t + 2 * offset, hit->patch);
          if (!other || other->t < hit->t - 2 * offset ||
              dot(dir, scene.patches[other->patch].polygon.plane.normal) >= 0)
            break;  // arrived on the back: absorbed
          hit = other;
        }
        const Patch& hp = scene.patches[hit->patch];
        const Rgb& rho = scene.materials[hp.material].reflectance;
        const Rgb refl{power.r * rho.r, power.g * rho.g, power.b * rho.b};
        Rgb& tally = batch.reflected[hit->patch];
        tally = {tally.r + refl.r, tally.g + refl.g, tally.b + refl.b};
        const double survive = std::min(1.0, std::max({rho.r, rho.g, rho.b}));
        if (!(survive > 0) || rng.uniform() >= survive) break;
        power = {refl.r / survive, refl.g / survive, refl.b / survive};
        origin = start + dir * hit->t;
        patch = hit->patch;
      }
    }
  });

  const double nb = static_cast<double>(batches);
  for (size_t k = 0; k < n; ++k) {
    if (!(areas[k] > 0)) continue;
    Rgb mean{}, sq{};
    for (const Batch& b : out) {
      const Rgb x{b.reflected[k].r / areas[k], b.reflected[k].g / areas[k],
                  b.reflected[k].b / areas[k]};
      mean = {mean.r + x.r / nb, mean.g + x.g / nb, mean.b + x.b / nb};
      sq = {sq.r + x.r * x.r / nb, sq.g + x.g * x.g / nb, sq.b + x.b * x.b / nb};
    }
    auto stderrOf = [nb](double m, double s) {
      return std::sqrt(std::max(0.0, s - m * m) / (nb - 1));
    };
    result.standardError[k] = {stderrOf(mean.r, sq.r), stderrOf(mean.g, sq.g),
                               stderrOf(mean.b, sq.b)};
    Rgb& b = result.radiosity[k];
    b = {b.r + mean.r, b.g + mean.g, b.b + mean.b};
  }
  result.photons = perBatch * batches;
  for (const uint32_t k : emitters) {
    // A photon's power in a batch over the batch count: its share of the mean of the batches.
    const Rgb& e = scene.materials[scene.patches[k].material].emission;
    const double scale = totalWeight / channelSum(e) / static_cast<double>(result.photons);
    Rgb& m = result.photonPower;
    m = {std::max(m.r, e.r * scale), std::max(m.g, e.g * scale), std::max(m.b, e.b * scale)};
  }
  for (const Batch& b : out) result.rays += b.rays;
  return result;
}

}  // namespace gv
