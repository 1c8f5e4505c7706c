// Ray vs blocker list (paper §6.3): whether one sample segment between two elements is blocked,
// tested against a tube's blockers only, by two plane evaluations and one Plücker inner product
// per blocker edge ("four 5D inner products" for a quadrilateral).
#pragma once

#include <cstdint>
#include <span>

#include "geometry/vec3.h"
#include "linespace/blocker_geometry.h"

namespace gv {

/// True when the open segment p → q meets one of `blockers` (ids into `table`): its end points
/// lie strictly on opposite sides of the blocker's plane (so the crossing is between them) and
/// the line's sides with all the blocker's edges have one sign; or an end point lies within
/// `contact` of the blocker's plane and inside the blocker (a point of an element covered by a
/// blocker resting on it; pass tol.length(), as the classification's contactCover does).
/// Floating point: a sample segment grazing an edge may go either way (a measure-zero set).
bool segmentBlocked(const Vec3& p, const Vec3& q, std::span<const uint32_t> blockers,
                    const BlockerTable& table, double contact);

/// The same test against one blocker.
bool segmentMeets(const Vec3& p, const Vec3& q, const PluckerLine& line, const BlockerGeometry& b,
                  double contact);

}  // namespace gv
