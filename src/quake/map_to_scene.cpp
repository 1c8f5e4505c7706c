// Quake .map → Scene. Choices (also in README):
// - Solid: worldspawn, func_group, func_detail*, func_wall and every other brush entity except the
//   non-solid ones below; movers (doors, plats, buttons, trains ...) in their spawn position unless
//   MapImportOptions::includeMovers is false. ericw-tools treats func_detail as solid for light.
// - Not solid (skipped): trigger_*, func_illusionary, func_detail_illusionary, info_*,
//   func_areaportal entities; brushes with a clip, hint*, origin, trigger or liquid (*...) face,
//   and brushes textured skip on every face.
// - Sky brushes stay solid so a sealed level stays sealed; their sky* faces become black
//   (absorbing) patches: light reaching the sky leaves the level, as under an open sky.
// - skip faces of solid brushes are not drawn (no patch) but their brush still hides others.
// - Brush planes closer than the model tolerance are merged first (PlaneSnapper, brush_csg.h), as
//   qbsp does, so that brushes meant to touch do touch.
// - Hidden surfaces: a face's parts inside another solid, or flat against an opposite-facing face
//   of one (two solids touching), are removed; of two coincident same-facing faces exactly one
//   is kept (that of the brush first in a fixed order: by least x, then file order).
//   func_detail_wall brushes clip nothing (ericw-tools: they do not clip the world), so the
//   faces behind their skip sides stay; one without a skip side is closed: the faces it hides
//   whole (inside it, or flat against it face to face) are dropped, and a face flat against it
//   in part loses that part; a face passing through it stays whole.
//   Coplanarity is decided within the model tolerance (Tolerance::planeOffset), the one the BSP
//   uses to merge planes.
// - Materials: one per texture name; Kd from a hash of the lower-cased name (see textureColour).
// - Lights: light and light_* entities → an outward cube of lightCubeSize at "origin", emitted
//   power kQuakeLightPowerPerValue × "light" (default 300), coloured by "_color"; the cube's parts
//   inside solids are removed like brush faces. A light with "_surface" is a template (ericw-tools
//   surface lights): no cube; every face with that texture emits the template's power per
//   "_surface_spacing"² (default 128²) of its area. Switchable lights that start off (a
//   targetname and spawnflags 1) are left dark: the solution is the level as it starts.
#include "quake/map_to_scene.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <map>
#include <sstream>
#include <tuple>

#include "quake/brush_csg.h"
#include "util/input_error.h"

namespace gv {
namespace {

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}
bool startsWith(const std::string& s, const char* prefix) {
  return s.rfind(prefix, 0) == 0;
}

enum class EntityKind { Solid, Mover, NonSolid };

EntityKind entityKind(const std::string& className) {
  const std::string c = lower(className);
  if (startsWith(c, "trigger_") || startsWith(c, "info_") || c == "func_illusionary" ||
      c == "func_detail_illusionary" || c == "func_areaportal")
    return EntityKind::NonSolid;
  static const char* const movers[] = {"func_door",      "func_door_secret", "func_plat",
                                       "func_button",    "func_train",       "func_rotating",
                                       "func_explosive", "func_movewall",    "func_bobbingwater",
                                       "func_breakable", "rotate_object"};
  for (const char* m : movers)
    if (c == m) return EntityKind::Mover;
  return EntityKind::Solid;
}

enum class BrushKind { Solid, Sky, Clip, Hint, Origin, Trigger, Liquid, SkipOnly };

BrushKind brushKind(const MapBrush& b) {
  bool sky = false, allSkip = true;
  for (const MapBrushSide& s : b.sides) {
    const std::string t = lower(s.texture);
    if (startsWith(t, "*")) return BrushKind::Liquid;
    if (t == "clip") return BrushKind::Clip;
    if (startsWith(t, "hint")) return BrushKind::Hint;
    if (t == "origin") return BrushKind::Origin;
    if (t == "trigger") return BrushKind::Trigger;
    sky = sky || startsWith(t, "sky");
    allSkip = allSkip && t == "skip";
  }
  if (allSkip) return BrushKind::SkipOnly;
  return sky ? BrushKind::Sky : BrushKind::Solid;
}

/// A plausible reflectance per texture: FNV-1a of the lower-cased name gives a grey level in
/// [0.3, 0.7] (the range of painted walls, stone and wood) tinted by up to ±10 % per channel, so
/// that different textures are told apart in pictures. Sky is black (it absorbs).
Rgb textureColour(const std::string& texture) {
  const std::string t = lower(texture);
  if (startsWith(t, "sky")) return {0, 0, 0};
  uint64_t h = 1469598103934665603ull;
  for (char c : t) {
    h ^= static_cast<unsigned char>(c);
    h *= 1099511628211ull;
  }
  auto unit = [&h](int shift) { return static_cast<double>((h >> shift) & 0xffff) / 65535.0; };
  const double grey = 0.3 + 0.4 * unit(0);
  return {grey * (0.9 + 0.2 * unit(16)), grey * (0.9 + 0.2 * unit(32)),
          grey * (0.9 + 0.2 * unit(48))};
}

std::vector<double> numbers(const std::string& text) {
  std::vector<double> out;
  std::istringstream in(text);
  std::string tok;
  while (in >> tok) {
    double v = 0;
    const auto [ptr, ec] = std::from_chars(tok.data(), tok.data() + tok.size(), v);
    if (ec != std::errc() || ptr != tok.data() + tok.size() || !std::isfinite(v)) return {};
    out.push_back(v);
  }
  return out;
}

/// A light / light_* entity's parameters. `surface` is the lower-cased "_surface" texture of a
/// surface-light template (ericw-tools: the light is copied across every face with that texture
/// instead of standing at its origin), empty for a point light.
struct LightEntity {
  Vec3 origin;
  double value = kQuakeDefaultLight;
  Rgb colour{1, 1, 1};
  std::string surface;
  double spacing = kQuakeSurfaceLightSpacing;
  /// A switchable light (it has a targetname) with spawnflag 1, START_OFF: dark until triggered.
  bool startsOff = false;
};

bool isLight(const MapEntity& e) {
  const std::string c = lower(e.className());
  return c == "light" || startsWith(c, "light_");
}

LightEntity parseLight(const MapEntity& e, const std::string& path) {
  LightEntity l;
  if (const std::string* surface = e.value("_surface")) l.surface = lower(*surface);
  const std::string* origin = e.value("origin");
  const std::vector<double> o = origin ? numbers(*origin) : std::vector<double>{};
  if (o.size() == 3)
    l.origin = {o[0], o[1], o[2]};
  else if (l.surface.empty() || origin)
    throw InputError(path, e.line, "light entity has no valid \"origin\" \"x y z\"");
  if (const std::string* value = e.value("light")) {
    const std::vector<double> v = numbers(*value);
    if (v.empty()) throw InputError(path, e.line, "light entity has a non-numeric \"light\" value");
    l.value = v.front();
  }
  if (const std::string* col = e.value("_color")) {
    const std::vector<double> v = numbers(*col);
    if (v.size() != 3 || *std::min_element(v.begin(), v.end()) < 0)
      throw InputError(path, e.line, "light entity has a malformed \"_color\" (want \"r g b\")");
    const double m = *std::max_element(v.begin(), v.end());
    if (m > 0) l.colour = {v[0] / m, v[1] / m, v[2] / m};  // 0..1 or 0..255: only the hue counts
  }
  if (const std::string* flags = e.value("spawnflags"); flags && e.value("targetname")) {
    const std::vector<double> v = numbers(*flags);
    if (v.size() != 1) throw InputError(path, e.line, "entity has a malformed \"spawnflags\"");
    l.startsOff = (static_cast<long long>(v[0]) & 1) != 0;
  }
  if (const std::string* spacing = e.value("_surface_spacing")) {
    const std::vector<double> v = numbers(*spacing);
    if (v.size() != 1 || v[0] <= 0)
      throw InputError(path, e.line, "light entity has a malformed \"_surface_spacing\"");
    l.spacing = v[0];
  }
  return l;
}

struct Solid {
  BrushSolid solid;
  const MapBrush* brush = nullptr;
  uint32_t firstSourceFace = 0;  ///< global index of the brush's first side
  bool sky = false;
  /// False for func_detail_wall, which by ericw-tools' definition does not clip the faces of
  /// other brushes (those stay drawn behind it; it often has skip faces that rely on them).
  /// Without a skip side it still drops the faces it hides whole and cuts those flat against it
  /// in part (see visibleOf).
  bool hidesOthers = true;
  bool skipSide = false;  ///< some face of the solid is textured skip (not drawn: it is open)
};

/// The parts of `face` that no solid other than `self` hides. Solids are sorted by box.lo.x.
std::vector<ConvexPolygon> visibleOf(const ConvexPolygon& face, size_t self,
                                     const std::vector<Solid>& solids, const Tolerance& tol) {
  const Aabb fb = face.bounds();
  const double on = tol.planeOffset();
  std::vector<ConvexPolygon> parts{face};
  for (size_t j = 0; j < solids.size() && !parts.empty(); ++j) {
    // A func_detail_wall brush does not clip other faces (see Solid::hidesOthers), but one with
    // no skip side is closed: a face it hides whole, inside it or flat against it face to
    // face, gets no light and is dropped (e3m4: such faces, flush with a brush side, let
    // `verify`'s rays leave them across that side within the contact distance: 4 pairs missed
    // in 10^6 rays). A face flat against it in part loses that part, for the same reason (e3m4:
    // a beam's bottom partly resting on such brushes, 1 pair missed). Faces passing through it
    // stay whole (cutting them too, as the world's brushes do, made e3m4 23,451 patches; this
    // rule makes 17,922, from 16,705), and where two faces share a surface facing one way both
    // stay (that tie could drop a drawn face for a skip side).
    if (j == self || (!solids[j].hidesOthers && solids[j].skipSide)) continue;
    const Aabb& ob = solids[j].solid.box;
    if (ob.lo.x > fb.hi.x + on) break;
    if (ob.hi.x < fb.lo.x - on || ob.lo.y > fb.hi.y + on || ob.hi.y < fb.lo.y - on ||
        ob.lo.z > fb.hi.z + on || ob.hi.z < fb.lo.z - on)
      continue;
    const CoplanarRule rule{j < self && solids[j].hidesOthers, on};
    std::vector<ConvexPolygon> next;
    for (ConvexPolygon& p : parts) {
      std::vector<ConvexPolygon> v = visibleParts(p, solids[j].solid.shape, rule, tol);
      if (!solids[j].hidesOthers) {
        if (v.empty()) continue;  // hidden whole
        const CoplanarRule flat{false, on, /*flatAgainstOnly=*/true};
        for (ConvexPolygon& q : visibleParts(p, solids[j].solid.shape, flat, tol))
          next.push_back(std::move(q));
        continue;
      }
      for (ConvexPolygon& q : v) next.push_back(std::move(q));
    }
    parts = std::move(next);
  }
  return parts;
}

std::vector<ConvexPolygon> cubeFaces(const Vec3& c, double half) {
  const Aabb box{c - Vec3{half, half, half}, c + Vec3{half, half, half}};
  std::optional<ConvexPolyhedron> cube = ConvexPolyhedron::fromAabb(box);
  std::vector<ConvexPolygon> out;
  if (cube)
    for (const PolyhedronFace& f : cube->faces) out.push_back(f.polygon);
  return out;
}

}  // namespace

double quakeLightEmission(double light, double cubeSize) {
  return kQuakeLightPowerPerValue * light / (6 * cubeSize * cubeSize);
}

double quakeSurfaceLightEmission(double light, double spacing) {
  return kQuakeLightPowerPerValue * light / (spacing * spacing);
}

Scene mapToScene(const MapFile& map, const std::string& path, const MapImportOptions& options,
                 MapImportStats* statsOut) {
  MapImportStats st;
  Scene scene;
  ImportReport& report = scene.report;
  for (const std::string& w : map.warnings) report.warnings.push_back(w);
  st.entities = map.entities.size();

  // 1. Which brushes are solid.
  std::vector<std::pair<const MapBrush*, uint32_t>> chosen;  // brush, first global side index
  std::vector<bool> chosenSky, chosenHides;
  Aabb pointBox;
  uint32_t sideIndex = 0;
  for (const MapEntity& e : map.entities) {
    const EntityKind ek = entityKind(e.className());
    for (const MapBrush& b : e.brushes) {
      ++st.brushesIn;
      const uint32_t first = sideIndex;
      sideIndex += static_cast<uint32_t>(b.sides.size());
      if (ek == EntityKind::NonSolid) {
        ++st.nonSolidEntityBrushes;
        continue;
      }
      if (ek == EntityKind::Mover) {
        ++st.moverBrushes;
        if (!options.includeMovers) continue;
      }
      switch (brushKind(b)) {
        case BrushKind::Clip:
          ++st.clipBrushes;
          continue;
        case BrushKind::Hint:
          ++st.hintBrushes;
          continue;
        case BrushKind::Origin:
          ++st.originBrushes;
          continue;
        case BrushKind::Trigger:
          ++st.triggerBrushes;
          continue;
        case BrushKind::Liquid:
          ++st.liquidBrushes;
          continue;
        case BrushKind::SkipOnly:
          ++st.skipOnlyBrushes;
          continue;
        case BrushKind::Sky:
          chosenSky.push_back(true);
          break;
        case BrushKind::Solid:
          chosenSky.push_back(false);
          break;
      }
      chosen.emplace_back(&b, first);
      chosenHides.push_back(lower(e.className()) != "func_detail_wall");
      for (const MapBrushSide& s : b.sides)
        for (const Vec3& p : s.points) pointBox.add(p);
    }
  }
  // The side points bound the level only roughly (an editor may put them anywhere on the
  // plane): the tolerance comes from the solids themselves, built once unsnapped to measure them.
  Aabb solidBox;
  const Tolerance rough = Tolerance::forBounds(pointBox);
  for (const auto& [brush, first] : chosen)
    if (std::optional<BrushSolid> s = brushSolid(*brush, rough)) solidBox.add(s->box);
  const Tolerance tol = Tolerance::forBounds(solidBox.empty() ? pointBox : solidBox);

  // 2. Solids (file order = priority for coincident faces), then sorted by x for the sweep.
  std::vector<Solid> solids;
  std::vector<size_t> degenerateLines;
  PlaneSnapper snapper(tol);
  for (size_t i = 0; i < chosen.size(); ++i) {
    std::optional<BrushSolid> s = brushSolid(*chosen[i].first, tol, &snapper);
    if (!s) {
      ++st.degenerateBrushes;
      degenerateLines.push_back(chosen[i].first->line);
      continue;
    }
    solids.push_back(
        {std::move(*s), chosen[i].first, chosen[i].second, chosenSky[i], chosenHides[i]});
    st.skyBrushes += chosenSky[i] ? 1 : 0;
    Solid& added = solids.back();
    for (const int side : added.solid.faceSide)
      added.skipSide = added.skipSide || lower(added.brush->sides[side].texture) == "skip";
  }
  st.solidBrushes = solids.size();
  // Stable sort keeps file order among equal keys; the tie rule compares sorted positions, which
  // is a fixed total order, so exactly one of two coincident faces survives either way.
  std::stable_sort(solids.begin(), solids.end(), [](const Solid& a, const Solid& b) {
    return a.solid.box.lo.x < b.solid.box.lo.x;
  });

  // 3. Visible parts of every face → patches, one material per texture; surface-light textures
  // emit (the template's power per spacing² of surface).
  std::map<std::string, Rgb> surfaceEmission;
  for (const MapEntity& e : map.entities) {
    if (!isLight(e) || !e.value("_surface")) continue;
    const LightEntity l = parseLight(e, path);
    ++st.surfaceLights;
    if (l.startsOff) ++st.startOffLights;
    if (l.value <= 0 || l.startsOff) continue;
    const double ke = quakeSurfaceLightEmission(l.value, l.spacing);
    Rgb& em = surfaceEmission[l.surface];  // several templates for one texture add up
    em = {em.r + ke * l.colour.r, em.g + ke * l.colour.g, em.b + ke * l.colour.b};
  }
  std::map<std::string, uint32_t> materialOf;
  auto materialFor = [&](const std::string& texture) {
    const std::string key = lower(texture);
    auto it = materialOf.find(key);
    if (it != materialOf.end()) return it->second;
    const auto em = surfaceEmission.find(key);
    const uint32_t id = scene.addMaterial(
        {key, textureColour(key), em == surfaceEmission.end() ? Rgb{} : em->second});
    materialOf.emplace(key, id);
    return id;
  };
  for (size_t i = 0; i < solids.size(); ++i) {
    const Solid& s = solids[i];
    for (size_t f = 0; f < s.solid.shape.faces.size(); ++f) {
      ++st.brushFaces;
      const int side = s.solid.faceSide[f];
      const std::string& texture = s.brush->sides[side].texture;
      const std::string t = lower(texture);
      if (t == "skip") {
        ++st.skipFaces;
        continue;
      }
      const ConvexPolygon& polygon = s.solid.shape.faces[f].polygon;
      std::vector<ConvexPolygon> parts = visibleOf(polygon, i, solids, tol);
      if (parts.empty()) {
        ++st.hiddenFaces;
        continue;
      }
      if (parts.size() > 1 || parts.front().vertices != polygon.vertices) ++st.cutFaces;
      if (startsWith(t, "sky")) ++st.skyFaces;
      const uint32_t material = materialFor(texture);
      if (scene.materials[material].isEmitter()) st.surfaceLightPatches += parts.size();
      for (ConvexPolygon& p : parts)
        scene.patches.push_back(
            {std::move(p), material, s.firstSourceFace + static_cast<uint32_t>(side)});
    }
  }

  // 4. Point lights.
  std::map<std::tuple<double, double, double>, uint32_t> lightMaterial;
  for (const MapEntity& e : map.entities) {
    if (!isLight(e) || e.value("_surface")) continue;
    const LightEntity l = parseLight(e, path);
    if (l.startsOff) {
      ++st.startOffLights;
      continue;
    }
    if (l.value <= 0) {
      ++st.skippedLights;
      continue;
    }
    std::vector<ConvexPolygon> faces;
    for (const ConvexPolygon& f : cubeFaces(l.origin, 0.5 * options.lightCubeSize))
      for (ConvexPolygon& p : visibleOf(f, solids.size(), solids, tol))
        faces.push_back(std::move(p));
    if (faces.empty()) {
      ++st.skippedLights;
      continue;
    }
    const double ke = quakeLightEmission(l.value, options.lightCubeSize);
    const Rgb emission{ke * l.colour.r, ke * l.colour.g, ke * l.colour.b};
    auto key = std::make_tuple(emission.r, emission.g, emission.b);
    auto it = lightMaterial.find(key);
    if (it == lightMaterial.end())
      it = lightMaterial
               .emplace(key, scene.addMaterial({"light_" + std::to_string(lightMaterial.size()),
                                                {0.8, 0.8, 0.8},
                                                emission}))
               .first;
    ++st.lights;
    for (ConvexPolygon& p : faces)
      scene.patches.push_back({std::move(p), it->second, kNoSourceFace});
  }
  st.patches = scene.patches.size();

  // 5. The report.
  report.facesIn = st.brushFaces;
  auto note = [&](size_t n, const std::string& what) {
    if (n > 0) report.warnings.push_back(path + ": " + std::to_string(n) + " " + what);
  };
  note(st.nonSolidEntityBrushes,
       "brush(es) of non-solid entities (trigger_*, func_illusionary, info_* ...) skipped");
  if (!options.includeMovers)
    note(st.moverBrushes, "mover brush(es) (doors, plats, buttons ...) skipped");
  note(st.clipBrushes, "clip brush(es) skipped");
  note(st.hintBrushes, "hint brush(es) skipped");
  note(st.originBrushes, "origin brush(es) skipped");
  note(st.triggerBrushes, "trigger-textured brush(es) skipped");
  note(st.liquidBrushes, "liquid brush(es) (*water, *slime, *lava ...) skipped as non-solid");
  note(st.skipOnlyBrushes, "brush(es) textured skip on every face skipped");
  if (st.degenerateBrushes > 0) {
    std::string lines;
    for (size_t k = 0; k < std::min<size_t>(degenerateLines.size(), 5); ++k)
      lines += (k ? ", " : "") + std::to_string(degenerateLines[k]);
    note(st.degenerateBrushes,
         "degenerate brush(es) dropped (collinear points, empty, flat or "
         "unbounded), at line(s) " +
             lines + (degenerateLines.size() > 5 ? ", ..." : ""));
  }
  note(st.skyFaces, "sky face(s) kept as black (absorbing) patches");
  note(st.skipFaces, "skip face(s) not drawn (their brushes stay solid)");
  note(st.skippedLights, "light(s) skipped (light value <= 0, or inside solids)");
  note(st.startOffLights, "switchable light(s) that start off (spawnflags 1) left dark");
  if (st.surfaceLights > 0)
    report.warnings.push_back(
        path + ": " + std::to_string(st.surfaceLights) +
        " surface-light template(s) (\"_surface\"): " + std::to_string(st.surfaceLightPatches) +
        " patch(es) of their textures emit instead");
  if (statsOut) *statsOut = st;
  if (scene.patches.empty())
    throw InputError(path, 0,
                     "the map has no visible solid face (" + std::to_string(st.brushesIn) +
                         " brushes, " + std::to_string(st.solidBrushes) + " solid)");
  return scene;
}

Scene importMap(const std::string& path, const MapImportOptions& options, MapImportStats* stats) {
  return mapToScene(readMapFile(path), path, options, stats);
}

}  // namespace gv
