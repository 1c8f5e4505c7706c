// PUNTs settled by the stabbing test of S, B, R. Paper §4.1 applied to §6.2.
#include "linespace/punt_resolution.h"

#include <algorithm>
#include <array>

#include "visibility/stabbing.h"

namespace gv {
namespace {

/// Is the sequence S, B (crossed along `along` = ±1 times its normal), R proven unstabbable?
/// Portal convention of stabbing.h: each loop counter-clockwise seen from where sightlines go,
/// i.e. its Newell normal is the direction of travel. Lines leave S through its front: S as it
/// is. They cross B along its normal (as it is) or against it (reversed). They arrive at R's
/// front travelling against R's normal: R reversed.
bool blocked(const Tube& tube, const BlockerGeometry& b, int along, bool clip,
             const Tolerance& tol) {
  std::array<Winding, 3> sequence;
  sequence[0] = tube.source().vertices;
  sequence[1] = b.vertices;
  if (along < 0) std::reverse(sequence[1].begin(), sequence[1].end());
  sequence[2] = tube.receiver().vertices;
  std::reverse(sequence[2].begin(), sequence[2].end());
  StabbingOptions options;
  options.clipBySeparatingPlanes = clip;
  options.seekWitness = false;  // only Blocked matters here
  return testPortalSequence(sequence, tol, options) == StabbingResult::Blocked;
}

}  // namespace

bool stabbingProvesDisjoint(const Tube& tube, const BlockerGeometry& b, int travel,
                            const Tolerance& tol) {
  if (travel != 0) return blocked(tube, b, travel, /*clip=*/true, tol);
  return blocked(tube, b, +1, /*clip=*/false, tol) && blocked(tube, b, -1, /*clip=*/false, tol);
}

}  // namespace gv
