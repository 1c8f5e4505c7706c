// Radiosity of contact-split pieces gathered back onto the patches they came from.
#include "report/piece_radiosity.h"

namespace gv {
namespace {

/// True when `piece` lies in `patch`'s plane, faces the same way and has its centroid inside it.
bool liesIn(const ConvexPolygon& piece, const ConvexPolygon& patch, const Tolerance& tol) {
  if (dot(piece.normal(), patch.normal()) < 1 - tol.normalCos()) return false;
  return patch.contains(piece.centroid(), tol);
}

}  // namespace

std::optional<std::vector<Rgb>> radiosityOnPatches(const Scene& patches, const Scene& pieces,
                                                   const std::vector<Rgb>& pieceRadiosity) {
  if (pieceRadiosity.size() != pieces.patches.size()) return std::nullopt;
  // The written files round coordinates: "in the plane" at the model tolerance.
  Tolerance tol = patches.tolerance();
  tol.scale *= kRelativeModelEpsilon / kRelativeLengthEpsilon;
  std::vector<Rgb> sum(patches.patches.size());
  std::vector<double> area(patches.patches.size(), 0.0);
  size_t k = 0;
  for (size_t j = 0; j < pieces.patches.size(); ++j) {
    const ConvexPolygon& piece = pieces.patches[j].polygon;
    // Advance to the next patch only once the current one has a piece.
    while (k < patches.patches.size() && !liesIn(piece, patches.patches[k].polygon, tol)) {
      if (area[k] == 0) return std::nullopt;
      ++k;
    }
    if (k == patches.patches.size()) return std::nullopt;
    const double a = piece.area();
    sum[k].r += a * pieceRadiosity[j].r;
    sum[k].g += a * pieceRadiosity[j].g;
    sum[k].b += a * pieceRadiosity[j].b;
    area[k] += a;
  }
  if (k + 1 != patches.patches.size()) return std::nullopt;
  for (size_t p = 0; p < sum.size(); ++p)
    sum[p] = {sum[p].r / area[p], sum[p].g / area[p], sum[p].b / area[p]};
  return sum;
}

}  // namespace gv
