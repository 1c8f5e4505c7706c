// Unoccluded diffuse form factors between convex polygons: the exact differential-area-to-polygon
// formula (Lambert's contour integral, as used by Nusselt / Baum et al. 1989) integrated over the
// receiving polygon with adaptive quadrature. The geometric kernel of hierarchical radiosity
// (HSA91 §3; paper §6: the "energetic interaction" of a link, before visibility).
#pragma once

#include <optional>
#include <span>

#include "geometry/convex_polygon.h"
#include "geometry/tolerance.h"
#include "geometry/vec3.h"

namespace gv {

/// Form factor from a differential area at `x` with unit normal `n` to the polygon `vertices`
/// (any orientation), counting only the part of the polygon in front of x's tangent plane:
/// F = (1 / 2π) Σ_i θ_i (n · g_i), θ_i the angle subtended at x by edge i, g_i the unit normal of
/// the plane through x and edge i. The polygon must lie in front of (or on) the tangent plane;
/// callers clip first (see formFactor). In [0, 1].
double pointToPolygonFormFactor(const Vec3& x, const Vec3& n, std::span<const Vec3> vertices);

/// pointToPolygonFormFactor from `x` on `plane` (normal = the plane's) to the part of `source`
/// in front of the plane (clipped when it straddles it; 0 when none is in front).
double pointFormFactorToFront(const Vec3& x, const Plane& plane, const ConvexPolygon& source,
                              const Tolerance& tol);

/// The parts of one-sided polygons `a` and `b` that exchange light: a clipped to the front of b's
/// plane and b to the front of a's (each unchanged when wholly in front). What formFactor
/// integrates over, and where visibility samples must lie: a sample behind the other's plane
/// stands for light that the form factor does not carry, and it is often blocked (the floor
/// under a block, seen from the block's side). nullopt when they cannot face.
struct ExchangingParts {
  ConvexPolygon a, b;
};
std::optional<ExchangingParts> exchangingParts(const ConvexPolygon& a, const ConvexPolygon& b,
                                               const Tolerance& tol);

/// Accuracy knobs of formFactor. The defaults reach ~1e-4 relative error on Howell's catalogue
/// cases, including rectangles that share an edge (where the integrand has a logarithmic
/// singularity along the edge and a fixed rule would be off by percents).
struct FormFactorOptions {
  /// Stop refining a quadrature triangle when the 7-point rule and the sum over its four children
  /// agree within this fraction of the whole integral's estimate (shared out by area).
  double relativeTolerance = 1e-3;
  /// Deepest refinement of a fan triangle of the receiver (4^depth sub-triangles at most).
  int maxDepth = 5;
};

/// The unoccluded form factor F(a → b) = (1 / A_a) ∫_a F(dA_x → b) dA_x from one-sided convex
/// polygon `a` to one-sided convex polygon `b`, both facing per their plane normals. Only the part
/// of `a` in front of b's plane and the part of `b` in front of a's plane exchange light; both are
/// clipped first. 0 when they cannot face. Reciprocity gives the other direction:
/// A_a F(a → b) = A_b F(b → a).
double formFactor(const ConvexPolygon& a, const ConvexPolygon& b, const Tolerance& tol,
                  const FormFactorOptions& options = {});

/// formFactor with an error bound for hierarchical radiosity. A link hands each receiving element
/// the *mean* of the point form factor over it; what that misses is how much the point form
/// factor varies across the receiver. `variationA` is max - min of F(dA_x → b) over sample points
/// x of a (its vertices pulled 1 % towards its centroid, the centroid, and a's point nearest to
/// b's centroid, pulled the same way; 0 counts as a sample
/// where part of a is clipped away behind b), `variationB` the same for F(dA_y → a) over b.
struct FormFactorEstimate {
  double ab = 0;          ///< F(a → b), as formFactor
  double variationA = 0;  ///< spread of F(dA_x → b) over a
  double variationB = 0;  ///< spread of F(dA_y → a) over b
};
FormFactorEstimate formFactorEstimate(const ConvexPolygon& a, const ConvexPolygon& b,
                                      const Tolerance& tol, const FormFactorOptions& options = {});

}  // namespace gv
