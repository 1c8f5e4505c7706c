// OBJ, Quake PRT1 and JSON output of the subdivision for viewing, for Quake tools and for the §7.1
// figures.
#include "bsp/subdivision_io.h"

#include <fmt/format.h>
#include <fmt/os.h>

#include <cstdio>
#include <memory>

#include "util/input_error.h"

namespace gv {
namespace {

using File = std::unique_ptr<std::FILE, int (*)(std::FILE*)>;

File openForWriting(const std::string& path) {
  File f(std::fopen(path.c_str(), "wb"), &std::fclose);
  if (!f) throw InputError(path, 0, "cannot open for writing");
  return f;
}

/// Writes a polygon's vertices and a face referring to them; `next` is the 1-based index of the
/// next OBJ vertex.
void writePolygon(std::FILE* f, const ConvexPolygon& p, size_t& next) {
  // %.17g round-trips doubles, so a viewer or a test sees exactly the computed geometry.
  for (const Vec3& v : p.vertices) fmt::print(f, "v {:.17g} {:.17g} {:.17g}\n", v.x, v.y, v.z);
  fmt::print(f, "f");
  for (size_t i = 0; i < p.vertices.size(); ++i) fmt::print(f, " {}", next + i);
  fmt::print(f, "\n");
  next += p.vertices.size();
}

void finish(File& f, const std::string& path) {
  if (std::ferror(f.get()) || std::fclose(f.release()) != 0) {
    throw InputError(path, 0, "write failed");
  }
}

}  // namespace

void writeCellsObj(const Subdivision& sub, const std::string& path) {
  File f = openForWriting(path);
  fmt::print(f.get(), "# globalvis cells: {} leaf cells of the BSP (paper §3)\n", sub.cells.size());
  size_t next = 1;
  for (size_t c = 0; c < sub.cells.size(); ++c) {
    fmt::print(f.get(), "g cell_{}\n", c);
    for (const PolyhedronFace& face : sub.cells[c].shape.faces)
      writePolygon(f.get(), face.polygon, next);
  }
  finish(f, path);
}

void writePortalsObj(const Subdivision& sub, const std::string& path) {
  File f = openForWriting(path);
  fmt::print(f.get(), "# globalvis portals: {} portals between leaf cells (paper §3)\n",
             sub.portals.size());
  size_t next = 1;
  for (size_t k = 0; k < sub.portals.size(); ++k) {
    const Portal& p = sub.portals[k];
    fmt::print(f.get(), "g portal_{}_{}_{}\n", k, p.back, p.front);
    writePolygon(f.get(), p.polygon, next);
  }
  finish(f, path);
}

void writePortalsPrt(const Subdivision& sub, const std::string& path) {
  File f = openForWriting(path);
  fmt::print(f.get(), "PRT1\n{}\n{}\n", sub.cells.size(), sub.portals.size());
  for (const Portal& p : sub.portals) {
    fmt::print(f.get(), "{} {} {}", p.polygon.vertices.size(), p.back, p.front);
    for (const Vec3& v : p.polygon.vertices) fmt::print(f.get(), " ({} {} {})", v.x, v.y, v.z);
    fmt::print(f.get(), "\n");
  }
  finish(f, path);
}

nlohmann::json statsJson(const SubdivisionStats& s) {
  return {{"patches", s.patches},
          {"planes", s.planes},
          {"bsp_nodes", s.nodes},
          {"bsp_depth", s.depth},
          {"leaf_cells", s.cells},
          {"portals", s.portals},
          {"mean_boundary_faces_per_cell", s.meanFacesPerCell},
          {"mean_coaffine_patches_per_cell", s.meanCoaffinePatchesPerCell},
          {"mean_portals_per_cell", s.meanPortalsPerCell},
          {"min_coverage", s.minCoverage},
          {"interior_area_fraction", s.interiorAreaFraction},
          {"sealed_cell_fraction", s.sealedCellFraction},
          {"blind_portal_fraction", s.blindPortalFraction},
          {"bsp_seconds", s.bspSeconds},
          {"portal_seconds", s.portalSeconds}};
}

}  // namespace gv
