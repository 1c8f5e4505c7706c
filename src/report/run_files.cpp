// Readers for the outputs of a pipeline run, and the run directory layout (see run_files.h).
#include "report/run_files.h"

#include <cmath>
#include <fstream>
#include <sstream>

#include "util/input_error.h"

namespace gv {
namespace {

namespace fs = std::filesystem;

/// The first of dir/sub/name for sub in `subs` (then dir/name) that exists, else empty.
fs::path firstExisting(const fs::path& dir, std::initializer_list<const char*> subs,
                       const char* name) {
  for (const char* sub : subs)
    if (fs::is_regular_file(dir / sub / name)) return dir / sub / name;
  if (fs::is_regular_file(dir / name)) return dir / name;
  return {};
}

std::ifstream openForReading(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path, 0, "cannot be opened for reading");
  return in;
}

}  // namespace

RunFiles findRunFiles(const fs::path& dir) {
  if (!fs::is_directory(dir)) throw InputError(dir.string(), 0, "not a directory");
  RunFiles f;
  f.dir = dir;
  f.patchesObj = firstExisting(dir, {"vis", "radiosity"}, "patches.obj");
  f.visibilityTxt = firstExisting(dir, {"vis"}, "visibility.txt");
  f.cellsObj = firstExisting(dir, {"cells"}, "cells.obj");
  f.portalsObj = firstExisting(dir, {"cells"}, "portals.obj");
  f.radiosityTxt = firstExisting(dir, {"radiosity"}, "radiosity.txt");
  f.elementsPly = firstExisting(dir, {"radiosity"}, "elements.ply");
  if (fs::is_regular_file(dir / "radiosity" / "patches.obj") &&
      f.patchesObj != dir / "radiosity" / "patches.obj")
    f.radiosityPatchesObj = dir / "radiosity" / "patches.obj";
  // stats.json has one name for three stages: only the subfolder layout tells them apart.
  for (auto [sub, out] : {std::pair{"cells", &f.cellsStats}, std::pair{"vis", &f.visStats},
                          std::pair{"radiosity", &f.radiosityStats}})
    if (fs::is_regular_file(dir / sub / "stats.json")) *out = dir / sub / "stats.json";
  return f;
}

std::vector<NamedPolygon> readObjPolygons(const std::string& path) {
  std::ifstream in = openForReading(path);
  std::vector<Vec3> vertices;
  std::vector<NamedPolygon> polygons;
  std::string group, line, tag;
  for (size_t lineNo = 1; std::getline(in, line); ++lineNo) {
    std::istringstream ss(line);
    if (!(ss >> tag) || tag[0] == '#') continue;
    if (tag == "v") {
      Vec3 v;
      if (!(ss >> v.x >> v.y >> v.z) || !std::isfinite(v.x) || !std::isfinite(v.y) ||
          !std::isfinite(v.z))
        throw InputError(path, lineNo, "expected `v x y z` with finite numbers");
      vertices.push_back(v);
    } else if (tag == "g") {
      ss >> group;
    } else if (tag == "f") {
      NamedPolygon p{group, {}};
      std::string ref;
      while (ss >> ref) {
        // `i`, `i/t`, `i/t/n` or `i//n`; negative indices count back from the last vertex.
        long index = 0;
        try {
          index = std::stol(ref.substr(0, ref.find('/')));
        } catch (const std::exception&) {
          throw InputError(path, lineNo, "bad vertex reference `" + ref + "`");
        }
        const long resolved = index < 0 ? long(vertices.size()) + index : index - 1;
        if (index == 0 || resolved < 0 || resolved >= long(vertices.size()))
          throw InputError(path, lineNo, "vertex index " + std::to_string(index) + " out of range");
        p.vertices.push_back(vertices[size_t(resolved)]);
      }
      if (p.vertices.size() < 3) throw InputError(path, lineNo, "a face needs 3 vertices");
      polygons.push_back(std::move(p));
    }
  }
  return polygons;
}

std::vector<long> groupNumbers(const std::string& group, size_t count, const std::string& path) {
  std::vector<long> numbers;
  std::istringstream ss(group.substr(std::min(group.find('_'), group.size())));
  char underscore;
  long n;
  while (ss >> underscore >> n && underscore == '_') numbers.push_back(n);
  if (numbers.size() != count)
    throw InputError(path, 0,
                     "group `" + group + "`: expected " + std::to_string(count) +
                         " numbers after the name, as `globalvis cells` writes them");
  return numbers;
}

std::vector<Rgb> readRadiosityTxt(const std::string& path, size_t patchCount) {
  std::ifstream in = openForReading(path);
  std::vector<Rgb> radiosity;
  std::string line;
  for (size_t lineNo = 1; std::getline(in, line); ++lineNo) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream ss(line);
    size_t patch = 0;
    Rgb b;
    if (!(ss >> patch >> b.r >> b.g >> b.b))
      throw InputError(path, lineNo, "expected `patch R G B`");
    if (patch != radiosity.size())
      throw InputError(path, lineNo,
                       "patch " + std::to_string(patch) + " out of order, expected " +
                           std::to_string(radiosity.size()));
    radiosity.push_back(b);
  }
  if (radiosity.size() != patchCount)
    throw InputError(path, 0,
                     std::to_string(radiosity.size()) + " patches, but patches.obj has " +
                         std::to_string(patchCount));
  return radiosity;
}

ElementMesh readElementsPly(const std::string& path) {
  std::ifstream in = openForReading(path);
  std::string line, word;
  size_t lineNo = 0;
  auto next = [&] {
    ++lineNo;
    if (!std::getline(in, line)) throw InputError(path, lineNo, "unexpected end of file");
    return std::istringstream(line);
  };
  if (next().str() != "ply" || next().str() != "format ascii 1.0")
    throw InputError(path, lineNo, "not an ASCII PLY file (`ply`, `format ascii 1.0`)");
  size_t vertexCount = 0, faceCount = 0;
  std::vector<std::string> vertexProperties;
  std::string element;
  for (;;) {
    std::istringstream ss = next();
    ss >> word;
    if (word == "end_header") break;
    if (word == "element") {
      size_t count = 0;
      if (!(ss >> element >> count)) throw InputError(path, lineNo, "bad element line");
      (element == "vertex" ? vertexCount : faceCount) = count;
    } else if (word == "property" && element == "vertex") {
      std::string type, name;
      ss >> type >> name;
      vertexProperties.push_back(name);
    }
  }
  auto column = [&](const char* name) {
    for (size_t i = 0; i < vertexProperties.size(); ++i)
      if (vertexProperties[i] == name) return i;
    throw InputError(path, 0, std::string("no vertex property `") + name + "`");
  };
  const size_t cx = column("x"), cy = column("y"), cz = column("z");
  const size_t cr = column("red"), cg = column("green"), cb = column("blue");
  ElementMesh mesh;
  std::vector<double> values(vertexProperties.size());
  for (size_t v = 0; v < vertexCount; ++v) {
    std::istringstream ss = next();
    for (double& x : values)
      if (!(ss >> x)) throw InputError(path, lineNo, "too few vertex properties");
    mesh.positions.push_back({values[cx], values[cy], values[cz]});
    mesh.colors.push_back({int(values[cr]), int(values[cg]), int(values[cb])});
  }
  for (size_t f = 0; f < faceCount; ++f) {
    std::istringstream ss = next();
    size_t n = 0;
    if (!(ss >> n) || n < 3) throw InputError(path, lineNo, "expected a face of >= 3 vertices");
    std::vector<uint32_t> face(n);
    for (uint32_t& i : face)
      if (!(ss >> i) || i >= vertexCount)
        throw InputError(path, lineNo, "missing or out-of-range vertex index");
    mesh.faces.push_back(std::move(face));
  }
  return mesh;
}

std::optional<nlohmann::json> readStatsJson(const fs::path& path) {
  if (path.empty()) return std::nullopt;
  std::ifstream in = openForReading(path.string());
  try {
    return nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw InputError(path.string(), 0, std::string("not valid JSON: ") + e.what());
  }
}

}  // namespace gv
