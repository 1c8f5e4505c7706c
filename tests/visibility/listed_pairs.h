// Whether a visibility graph lists a pair: the check the propagation tests make on `vis`'s
// output for the pairs their ray witnesses prove visible.
#pragma once

#include <algorithm>
#include <cstdint>

#include "visibility/visibility_graph.h"

namespace gv::test {

/// Whether the unordered pair (a, b) is listed (VISIBLE or PARTIAL).
inline bool listed(const VisibilityGraph& g, uint32_t a, uint32_t b) {
  const uint32_t s = std::min(a, b), r = std::max(a, b);
  return std::any_of(g.interactions.begin(), g.interactions.end(),
                     [&](const Interaction& in) { return in.s == s && in.r == r; });
}

/// Whether the pair (a, b) is listed with `blocker` in its blocker list.
inline bool hasBlocker(const VisibilityGraph& g, uint32_t a, uint32_t b, uint32_t blocker) {
  const uint32_t s = std::min(a, b), r = std::max(a, b);
  return std::any_of(g.interactions.begin(), g.interactions.end(), [&](const Interaction& in) {
    return in.s == s && in.r == r &&
           std::find(in.blockers.begin(), in.blockers.end(), blocker) != in.blockers.end();
  });
}

}  // namespace gv::test
