// Quake portal files (.prt, written by qbsp): the convex leafs (or clusters) of a level and the
// portals between them, the input of a potentially-visible-set computation (paper §4 applied to
// game levels). Formats PRT1 and PRT2 as described in shared/data/quake/README.md.
#pragma once

#include <istream>
#include <string>
#include <vector>

#include "geometry/vec3.h"

namespace gv {

/// One portal of a .prt file: a convex polygon between two clusters.
struct PrtPortal {
  /// Vertices as in the file. Their counter-clockwise (Newell) normal points from `clusterA` into
  /// `clusterB` (qbsp writes the front leaf first; checked on every shared map by the tests).
  std::vector<Vec3> winding;
  int clusterA = 0;
  int clusterB = 0;
  size_t line = 0;  ///< 1-based line in the file, for messages
};

/// A parsed portal file. For PRT1 the clusters are the leafs (leafCluster[i] == i); for PRT2
/// portals link clusters (convex regions, each the union of the leafs listed for it).
struct PrtFile {
  int version = 1;  ///< 1 or 2
  size_t leafCount = 0;
  size_t clusterCount = 0;
  std::vector<PrtPortal> portals;
  std::vector<int> leafCluster;                ///< cluster of each leaf
  std::vector<std::vector<int>> clusterLeafs;  ///< leafs of each cluster, ascending
  size_t selfPortalsSkipped = 0;               ///< portals from a cluster to itself (ignored)
};

/// Reads a .prt file. Throws InputError(path, line, message) on anything malformed: missing
/// file, unknown header, bad or inconsistent counts, non-finite or unparsable coordinates, fewer
/// than 3 points, leaf/cluster ids out of range, a leaf in no cluster or in two.
PrtFile readPrtFile(const std::string& path);

/// As readPrtFile, from a stream; `name` is used in error messages.
PrtFile parsePrt(std::istream& in, const std::string& name);

}  // namespace gv
