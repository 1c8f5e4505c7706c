// BSP construction over patch support planes with the paper's split heuristic. Paper §3.
#include "bsp/bsp_tree.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <utility>

#include "bsp/coplanar_clip.h"

namespace gv {
namespace {

/// The section of a convex cell by a plane, counter-clockwise about the plane's normal: a square
/// larger than the cell, clipped by every halfspace. nullopt when the plane misses the cell or
/// only grazes it (the section would be thinner than the tolerance).
std::optional<ConvexPolygon> sectionOf(const ConvexPolyhedron& cell, const Plane& plane,
                                       const Tolerance& tol) {
  const Aabb box = cell.bounds();
  const Vec3& n = plane.normal;
  const auto [u, v] = perpendicularFrame(n);
  const Vec3 c = box.center() - n * plane.distance(box.center());
  const double h = box.diagonal();
  std::optional<ConvexPolygon> section = ConvexPolygon{
      {c - u * h - v * h, c + u * h - v * h, c + u * h + v * h, c - u * h + v * h}, plane};
  for (const Plane& halfspace : cell.halfspaces) {
    section = clipToFront(*section, halfspace.flipped(), tol);
    if (!section) return std::nullopt;
  }
  return section;
}

double perimeter(const ConvexPolygon& p) {
  double sum = 0;
  for (size_t i = 0; i < p.vertices.size(); ++i) {
    sum += distance(p.vertices[i], p.vertices[(i + 1) % p.vertices.size()]);
  }
  return sum;
}

/// The fragments of one plane inside a cell: a candidate splitter.
struct Group {
  uint32_t plane = 0;
  std::vector<uint32_t> members;  ///< indices into the cell's fragments
  double area = 0;                ///< sum of the members' areas (overlaps counted twice)
};

/// How good a split is; compared lexicographically (bigger is better).
struct Score {
  bool covers = false;  ///< the fragments cover the whole section: the halves cannot see each other
  double coverage = 0;  ///< fragment area / section area, at most 1
  double centrality = 0;  ///< minus the plane's distance from the cell's centre, over its size
  bool operator<(const Score& o) const {
    if (covers != o.covers) return !covers;
    if (coverage != o.coverage) return coverage < o.coverage;
    return centrality < o.centrality;
  }
};

/// A cell waiting to be split, and where to hang the result.
struct Work {
  ConvexPolyhedron cell;
  std::vector<PatchFragment> fragments;
  std::vector<PatchFragment> resting;  ///< fragments on planes that only graze the cell
  int32_t parent = -1;                 ///< node to link to (-1: this is the root)
  bool isFront = false;                ///< which child of `parent`
  int depth = 0;
};

class Builder {
 public:
  Builder(const BspOptions& options, BspTree& tree)
      : options_(options), tree_(tree), tol_(tree.tol) {}

  void run(Work root) {
    if (options_.progress) rootVolume_ = root.cell.volume();
    std::vector<Work> stack;
    stack.push_back(std::move(root));
    while (!stack.empty()) {
      Work work = std::move(stack.back());
      stack.pop_back();
      process(std::move(work), stack);
    }
  }

 private:
  void link(const Work& work, int32_t child) {
    if (work.parent < 0) return;
    BspNode& parent = tree_.nodes[static_cast<size_t>(work.parent)];
    (work.isFront ? parent.front : parent.back) = child;
  }

  void makeLeaf(Work& work) {
    BspLeaf leaf{std::move(work.cell), std::move(work.resting)};
    for (PatchFragment& f : work.fragments) leaf.interior.push_back(std::move(f));
    link(work, leafChild(static_cast<uint32_t>(tree_.leaves.size())));
    tree_.leaves.push_back(std::move(leaf));
    tree_.depth = std::max(tree_.depth, work.depth);
    if (options_.progress) {
      doneVolume_ += tree_.leaves.back().shape.volume();
      options_.progress(doneVolume_ / rootVolume_);
    }
  }

  /// The fragments of `work` grouped by plane, largest total area first, without the planes
  /// that are too small to split on at all.
  std::vector<Group> groups(const Work& work) const {
    std::vector<uint32_t> order(work.fragments.size());
    for (uint32_t i = 0; i < order.size(); ++i) order[i] = i;
    std::sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) {
      return work.fragments[a].plane < work.fragments[b].plane;
    });
    std::vector<Group> out;
    for (uint32_t i : order) {
      const PatchFragment& f = work.fragments[i];
      if (out.empty() || out.back().plane != f.plane) out.push_back({f.plane, {}, 0});
      out.back().members.push_back(i);
      out.back().area += f.polygon.area();
    }
    const double minArea = options_.minRelativeArea * tol_.scale * tol_.scale;
    std::erase_if(out, [&](const Group& g) { return g.area < minArea; });
    std::stable_sort(out.begin(), out.end(),
                     [](const Group& a, const Group& b) { return a.area > b.area; });
    return out;
  }

  /// True when the group's fragments leave nothing of `section` uncovered (within tolerance).
  bool covers(const ConvexPolygon& section, const Group& g, const Work& work) const {
    // Largest first: a slab's big face usually covers all at once, leaving nothing to cut.
    std::vector<uint32_t> members = g.members;
    std::sort(members.begin(), members.end(), [&](uint32_t a, uint32_t b) {
      return work.fragments[a].polygon.area() > work.fragments[b].polygon.area();
    });
    std::vector<ConvexPolygon> rest{section}, next;
    for (uint32_t i : members) {
      const ConvexPolygon& fragment = work.fragments[i].polygon;
      const Aabb fb = fragment.bounds();
      next.clear();
      for (ConvexPolygon& piece : rest) {
        if (!overlaps(piece.bounds(), fb)) {
          next.push_back(std::move(piece));
        } else {
          subtractCoplanar(piece, fragment, tol_, next);
        }
      }
      std::swap(rest, next);
      if (rest.empty()) return true;
    }
    return false;
  }

  bool overlaps(const Aabb& a, const Aabb& b) const {
    const double e = tol_.length();
    for (int k = 0; k < 3; ++k) {
      if (a.lo[k] > b.hi[k] + e || b.lo[k] > a.hi[k] + e) return false;
    }
    return true;
  }

  void process(Work work, std::vector<Work>& stack) {
    for (;;) {
      const std::vector<Group> all = groups(work);
      if (all.empty()) return makeLeaf(work);
      const Aabb box = work.cell.bounds();
      const Vec3 centre = box.center();
      const double size = std::max(box.diagonal(), tol_.length());
      const auto& planes = tree_.planes.planes();

      // Score the planes in batches, largest fragment area first; a later batch is looked at
      // only when no plane of the earlier ones qualified.
      std::vector<uint32_t> grazing;  // groups whose plane misses or grazes the cell
      const Group* best = nullptr;
      Score bestScore;
      const size_t batch = static_cast<size_t>(std::max(1, options_.maxCandidates));
      for (size_t start = 0; start < all.size() && !best; start += batch) {
        // Score by coverage first; the exact (costly) "covers the whole section" test is run
        // afterwards, most central first, only on planes whose area could cover it.
        struct Candidate {
          const Group* group;
          ConvexPolygon section;
          Score score;
          bool mayCover;
        };
        std::vector<Candidate> scored;
        for (size_t k = start; k < std::min(all.size(), start + batch); ++k) {
          const Group& g = all[k];
          const Plane& plane = planes[g.plane];
          std::optional<ConvexPolygon> section = sectionOf(work.cell, plane, tol_);
          if (!section) {
            grazing.push_back(static_cast<uint32_t>(k));
            continue;
          }
          const double sectionArea = section->area();
          Score s;
          s.coverage = std::min(1.0, g.area / sectionArea);
          if (s.coverage < options_.minCoverage) continue;
          s.centrality = -std::abs(plane.distance(centre)) / size;
          const double slack =
              tol_.length() * perimeter(*section) * static_cast<double>(g.members.size() + 1);
          scored.push_back({&g, std::move(*section), s, g.area >= sectionArea - slack});
        }
        std::sort(scored.begin(), scored.end(), [](const Candidate& a, const Candidate& b) {
          return a.score.centrality > b.score.centrality;
        });
        for (Candidate& c : scored) {
          if (c.mayCover && covers(c.section, *c.group, work)) {
            c.score.covers = true;
            c.score.coverage = 1;
            best = c.group;
            bestScore = c.score;
            break;  // the most central covering plane
          }
        }
        if (best) break;
        for (const Candidate& c : scored) {
          if (!best || bestScore < c.score) best = c.group, bestScore = c.score;
        }
      }
      if (best) {
        const Group chosen = *best;  // `all` dies with this iteration
        PolyhedronSplit parts =
            split(work.cell, planes[chosen.plane], tol_, static_cast<int>(tree_.nodes.size()));
        if (parts.front && parts.back) return splitWork(work, chosen, parts, stack);
        // The cut is not a real one (rounding): the plane only grazes the cell.
        grazing.push_back(static_cast<uint32_t>(best - all.data()));
      }
      if (grazing.empty()) return makeLeaf(work);
      // Set the grazing planes' fragments aside and choose again.
      std::vector<bool> rests(work.fragments.size(), false);
      for (uint32_t k : grazing) {
        for (uint32_t i : all[k].members) rests[i] = true;
      }
      std::vector<PatchFragment> kept;
      for (size_t i = 0; i < work.fragments.size(); ++i) {
        (rests[i] ? work.resting : kept).push_back(std::move(work.fragments[i]));
      }
      work.fragments = std::move(kept);
    }
  }

  void splitWork(Work& work, const Group& chosen, PolyhedronSplit& parts,
                 std::vector<Work>& stack) {
    const auto nodeId = static_cast<int32_t>(tree_.nodes.size());
    BspNode node;
    node.plane = chosen.plane;
    node.splitter = tree_.planes.planes()[chosen.plane];
    Work front{std::move(*parts.front), {}, {}, nodeId, true, work.depth + 1};
    Work back{std::move(*parts.back), {}, {}, nodeId, false, work.depth + 1};
    for (PatchFragment& f : work.fragments) {
      if (f.plane == chosen.plane) {
        node.coplanar.push_back(std::move(f));
        continue;
      }
      PolygonSplit s = split(f.polygon, node.splitter, tol_);
      if (s.on) {
        // Another plane, but this fragment lies on the splitter within tolerance: it is part of
        // the boundary between the halves, so it is opaque there.
        node.coplanar.push_back({f.patch, f.plane, std::move(*s.on)});
        continue;
      }
      if (s.front) front.fragments.push_back({f.patch, f.plane, std::move(*s.front)});
      if (s.back) back.fragments.push_back({f.patch, f.plane, std::move(*s.back)});
    }
    // A resting fragment lies on a plane that only grazes the cell: it is split like the others
    // but never becomes a splitter; the children record it as lying in (or on) them.
    for (PatchFragment& f : work.resting) {
      PolygonSplit s = split(f.polygon, node.splitter, tol_);
      if (s.on) front.resting.push_back(std::move(f));
      if (s.front) front.resting.push_back({f.patch, f.plane, std::move(*s.front)});
      if (s.back) back.resting.push_back({f.patch, f.plane, std::move(*s.back)});
    }
    link(work, nodeId);
    tree_.nodes.push_back(std::move(node));
    stack.push_back(std::move(back));
    stack.push_back(std::move(front));
  }

  const BspOptions& options_;
  BspTree& tree_;
  const Tolerance tol_;
  double rootVolume_ = 1, doneVolume_ = 0;  ///< for options_.progress
};

}  // namespace

uint32_t BspTree::leafAt(const Vec3& p) const {
  if (nodes.empty()) return 0;
  int32_t child = 0;
  while (child >= 0) {
    const BspNode& n = nodes[static_cast<size_t>(child)];
    child = n.splitter.distance(p) > 0 ? n.front : n.back;
  }
  return leafOf(child);
}

BspTree buildBspTree(const Scene& scene, const BspOptions& options) {
  if (scene.patches.empty()) throw std::invalid_argument("buildBspTree: the scene has no patches");
  BspTree tree;
  const Aabb bounds = scene.bounds();
  tree.tol = Tolerance::forBounds(bounds);
  tree.planes = PlaneSet::fromScene(scene, tree.tol);

  const double margin = kRootMarginFraction * tree.tol.scale;
  Aabb rootBox = bounds;
  rootBox.lo -= Vec3{margin, margin, margin};
  rootBox.hi += Vec3{margin, margin, margin};
  std::optional<ConvexPolyhedron> root = ConvexPolyhedron::fromAabb(rootBox);
  if (!root) throw std::invalid_argument("buildBspTree: the scene's bounds are not finite");
  tree.root = *root;

  Work work;
  work.cell = std::move(*root);
  work.fragments.reserve(scene.patches.size());
  for (uint32_t i = 0; i < scene.patches.size(); ++i) {
    // Fragments live exactly on their merged plane: a patch merged from up to planeOffset away
    // would otherwise be cut by a tilted splitter along a line shifted from where the cells'
    // faces (which lie on the merged plane) are cut, leaving slivers of false portal.
    const PatchPlane& pp = tree.planes.of(i);
    const Plane& plane = tree.planes.planes()[pp.plane];
    ConvexPolygon projected{scene.patches[i].polygon.vertices,
                            pp.facesAlong ? plane : plane.flipped()};
    for (Vec3& v : projected.vertices) v -= plane.normal * plane.distance(v);
    work.fragments.push_back({i, pp.plane, std::move(projected)});
  }
  Builder(options, tree).run(std::move(work));
  return tree;
}

}  // namespace gv
