// Linespace tubes (paper §6.1, §6.2): the extremal lines between two convex elements and the
// classification of one blocker against them into the paper's four outcomes (Fig. 11), with the
// plane tests that make "occludes completely" sound and, beyond the paper, PUNTs settled by the
// stabbing test of the sequence S, B, R (§4.1).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "geometry/convex_polygon.h"
#include "geometry/tolerance.h"
#include "linespace/blocker_geometry.h"
#include "linespace/filtered_line.h"

namespace gv {

/// The paper's four outcomes of classifying one blocker B against a tube (Fig. 11).
enum class BlockerOutcome : uint8_t {
  Occludes,  ///< every segment from S to R meets B: the interaction is INVISIBLE
  Impinges,  ///< B is kept: some extremal line meets it and some does not
  Disjoint,  ///< no segment from the front of S to the front of R meets B: drop it
  Punt,      ///< undecided: B is kept (conservative)
};

/// One blocker's classification and how it was reached.
struct BlockerVerdict {
  BlockerOutcome outcome = BlockerOutcome::Punt;
  /// S and R lie on opposite sides of B's plane (the only case where B can occlude completely).
  bool between = false;
  /// Decided by plane tests alone (B behind S or R, or S and R on one side of B's plane).
  bool byPlanes = false;
  /// The line tests said PUNT; `outcome` is then the stabbing test's answer (Disjoint when it
  /// proved that no line crosses S, B and R, Punt otherwise).
  bool wasPunt = false;
};

/// Options of the classification.
struct TubeOptions {
  /// Settle PUNTs by the stabbing-line LP of the sequence S, B, R (exact up to the LP's margin;
  /// an order of magnitude slower than the line tests, and only run on PUNTs).
  bool resolvePunts = true;
  /// When B's plane cuts S or R, classify the two clipped "between" sub-problems instead of
  /// only the weaker straddling line test (tube.cpp). Off: the paper's tests alone.
  bool splitStraddling = true;
  /// When no single blocker occludes, try coplanar groups of between blockers jointly
  /// (geometry/coplanar_cover.h): a wall of several patches makes the tube INVISIBLE.
  bool coplanarCover = true;
};

/// The set of segments from a source element S to a receiver element R in linespace: the
/// extremal lines through each vertex of S and each vertex of R (|S| x |R| of them; 16 for two
/// quadrilaterals), oriented S → R.
class Tube {
 public:
  Tube(const ConvexPolygon& source, const ConvexPolygon& receiver);

  const ConvexPolygon& source() const { return source_; }
  const ConvexPolygon& receiver() const { return receiver_; }
  /// Line from source vertex i to receiver vertex j at index i * receiver().vertices.size() + j.
  std::span<const FilteredLine> extremalLines() const { return lines_; }

 private:
  ConvexPolygon source_, receiver_;
  std::vector<FilteredLine> lines_;
};

/// How much of an element a blocker lying on the element's plane covers.
enum class ContactCover : uint8_t { None, Part, All };
/// None unless every vertex of `b` lies within tol.length() of the element's plane; then All when
/// the element lies inside b, Part when they overlap in more than a sliver, else None.
ContactCover contactCover(const ConvexPolygon& element, const BlockerGeometry& b,
                          const Tolerance& tol);

/// Classifies blocker `b` against the tube (see tube.cpp for why each outcome is sound).
/// `tol.length()` decides "on a plane" for the plane tests; the line tests are exact.
BlockerVerdict classifyBlocker(const Tube& tube, const BlockerGeometry& b, const Tolerance& tol,
                               const TubeOptions& options = {});

}  // namespace gv
