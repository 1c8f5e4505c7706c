#!/usr/bin/env python3
"""Quake 3 / OpenArena BSP (IBSP version 46) -> Wavefront OBJ + MTL "brush soup".

Writes the solid brushes of a level's world (model 0) the way the shared reference levels
(../shared/data/levels/q3-*.obj, lit-q3-*.obj) were made:

- Coordinates are map units / 32, z up, printed "%.6f". Every face gets its own vertices.
- A brush is solid when the contents of its own shader (brush.shaderNum in the BSP's shaders lump)
  have CONTENTS_SOLID (1). Water, lava, slime, fog, playerclip/monsterclip, nodraw-only clip,
  nodrop, donotenter, areaportal and other non-solid brushes are skipped whole. Brushes of other
  models (doors, platforms, ...) are skipped.
- Every side of a solid brush becomes one convex polygon facing out of the brush (vertex order
  counter-clockwise seen from outside): q3map's BaseWindingForPlane square (half size 100000,
  but with its edges exactly orthogonal to the stored, not quite unit, normal), vertices
  reversed, then Sutherland-Hodgman clipped in double precision by the planes of all the brush's
  other sides in BSP order (a vertex with distance <= 0 is kept; sides on the opposite plane are
  skipped). Bevel sides (shader "noshader") are output too. A polygon with fewer than 3 vertices
  or a Newell area below 5e-4 square map units is dropped; nothing else is snapped or merged, so
  slivers and repeated vertices of near-degenerate bevels stay, as in the references.
- Plain output: materials `wall` (Kd 0.6, no emission) and `sky` (Ke 1): sides whose shader has
  SURF_SKY in the BSP or `surfaceparm sky` in its script.
- Lit output (--lit): one material per side shader, in order of first use. Shaders whose script
  has q3map_surfacelight >= 300 are `glow:<shader>` with Kd 0 and Ke (5, 4.85, 4.5), lava
  shaders (3, 1.35, 0.3), sky shaders 0 (the lit variants' sky does not emit); all others are
  `q3:<shader>` with a grey-ish Kd from the CRC-32 of the shader name. The header gives the
  emitted power (sum of area x Ke, output units). Beyond the references (their maps have
  neither): every `light` entity becomes an emitting cube of 8 map units at its origin (halved
  up to twice if it would overlap a solid brush, else skipped), total power 300*pi*"light"
  (map units^2), coloured by "_color"; and a level with no emitter at all gets its sky faces
  emitting Ke 1 (as in the plain variant) instead of being dark.

Usage:
  q3bsp_to_obj.py SOURCE [-o OUTDIR] [--name BASENAME] [--lit | --both] [--pk3-dir DIR]
SOURCE is a .bsp file or PK3:maps/NAME.bsp (a zip path, a colon, the member name). Writes
OUTDIR/BASENAME.obj + .mtl (plain) and/or OUTDIR/lit-BASENAME.obj + .mtl (lit). BASENAME
defaults to the map's name (NAME). The shader scripts are read from every *.pk3 of --pk3-dir
(default: the PK3's folder, else /usr/share/games/openarena/baseoa), later files overriding
earlier ones. Standard library only.
"""
import argparse
import glob
import math
import os
import re
import struct
import sys
import zipfile
import zlib

CONTENTS_SOLID = 0x1
CONTENTS_LAVA = 0x8
SURF_SKY = 0x4

SCALE = 32.0               # map units per output unit
BASE_HALF_SIZE = 100000.0  # half size of the base square on each plane (map units)
MIN_AREA = 5e-4            # polygons below this Newell area (square map units) are dropped
GLOW_MIN_SURFACELIGHT = 300.0
GLOW_KE = (5.0, 4.85, 4.5)
LAVA_KE = (3.0, 1.35, 0.3)
# Light entities (not covered by the references): a cube of LIGHT_CUBE map units at the origin,
# total power LIGHT_POWER_PER_VALUE * "light" (square map units x radiosity, the project's
# Quake importer's kQuakeLightPowerPerValue), coloured by "_color".
LIGHT_CUBE = 8.0
LIGHT_POWER_PER_VALUE = 300.0 * math.pi
LIGHT_DEFAULT = 300.0
DEFAULT_PK3_DIR = "/usr/share/games/openarena/baseoa"


# ---------------------------------------------------------------------------------------------
# BSP reading
# ---------------------------------------------------------------------------------------------
class Bsp:
    def __init__(self, data, label):
        if data[:4] != b"IBSP":
            raise ValueError("%s: not an IBSP file" % label)
        version = struct.unpack_from("<i", data, 4)[0]
        if version != 46:
            raise ValueError("%s: IBSP version %d, want 46 (Quake 3 / OpenArena)" % (label, version))
        lumps = [struct.unpack_from("<ii", data, 8 + 8 * i) for i in range(17)]

        def lump(i):
            off, length = lumps[i]
            return data[off:off + length]

        self.entities = lump(0).split(b"\0")[0].decode("latin-1")
        raw = lump(1)
        self.shaders = []  # (name, surfaceFlags, contents)
        for i in range(len(raw) // 72):
            name = raw[i * 72:i * 72 + 64].split(b"\0")[0].decode("latin-1")
            flags, contents = struct.unpack_from("<ii", raw, i * 72 + 64)
            self.shaders.append((name, flags, contents))
        raw = lump(2)
        self.planes = [struct.unpack_from("<4f", raw, i * 16) for i in range(len(raw) // 16)]
        raw = lump(7)
        self.models = [struct.unpack_from("<6f4i", raw, i * 40) for i in range(len(raw) // 40)]
        raw = lump(8)
        self.brushes = [struct.unpack_from("<3i", raw, i * 12) for i in range(len(raw) // 12)]
        raw = lump(9)
        self.sides = [struct.unpack_from("<2i", raw, i * 8) for i in range(len(raw) // 8)]

    def shader(self, index):
        if 0 <= index < len(self.shaders):
            return self.shaders[index]
        return ("noshader", 0, 0)


def read_source(source):
    """Returns (bytes, header text, map name, pk3 path or None)."""
    if os.path.isfile(source):
        with open(source, "rb") as f:
            data = f.read()
        name = os.path.splitext(os.path.basename(source))[0]
        return data, os.path.basename(source), name, None
    m = re.match(r"^(.*\.pk3):(.+)$", source, re.IGNORECASE)
    if not m:
        raise ValueError("%s: no such file, and not PK3:maps/NAME.bsp" % source)
    pk3, member = m.group(1), m.group(2)
    with zipfile.ZipFile(pk3) as z:
        names = {n.lower(): n for n in z.namelist()}
        real = names.get(member.lower())
        if real is None:
            raise ValueError("%s has no %s" % (pk3, member))
        data = z.read(real)
    name = os.path.splitext(os.path.basename(member))[0]
    return data, "%s from %s" % (member, os.path.basename(pk3)), name, pk3


# ---------------------------------------------------------------------------------------------
# Brush geometry (double precision on the stored float planes; see the module docstring)
# ---------------------------------------------------------------------------------------------
def base_winding(n, d):
    """A square of half size BASE_HALF_SIZE on the plane n.x = d, counter-clockwise seen from the
    front. As q3map's BaseWindingForPlane (axis "up" from the normal's major axis, origin n*d),
    but right = unit(up x n) and up = n x right, so the square lies exactly in the plane of the
    stored, not quite unit, normal."""
    nx, ny, nz = n
    ax = max(range(3), key=lambda i: abs(n[i]))
    a = (0.0, 0.0, 1.0) if ax in (0, 1) else (1.0, 0.0, 0.0)
    right = [a[1] * nz - a[2] * ny, a[2] * nx - a[0] * nz, a[0] * ny - a[1] * nx]
    length = math.sqrt(right[0] * right[0] + right[1] * right[1] + right[2] * right[2])
    right = [c / length for c in right]
    up = [ny * right[2] - nz * right[1], nz * right[0] - nx * right[2], nx * right[1] - ny * right[0]]
    org = [nx * d, ny * d, nz * d]
    up = [c * BASE_HALF_SIZE for c in up]
    right = [c * BASE_HALF_SIZE for c in right]
    w = [[org[i] - right[i] + up[i] for i in range(3)],
         [org[i] + right[i] + up[i] for i in range(3)],
         [org[i] + right[i] - up[i] for i in range(3)],
         [org[i] - right[i] - up[i] for i in range(3)]]
    return w[::-1]  # q3map's order is clockwise seen from the front; ours is counter-clockwise


def clip_back(w, n, d):
    """Keeps the part of w behind the plane n.x = d (distance <= 0); None when < 3 vertices."""
    nx, ny, nz = n
    ds = [p[0] * nx + p[1] * ny + p[2] * nz - d for p in w]
    count = len(w)
    out = []
    for i in range(count):
        p = w[i]
        j = i + 1 if i + 1 < count else 0
        inside_p = ds[i] <= 0
        if inside_p:
            out.append(p)
        if inside_p != (ds[j] <= 0):
            q = w[j]
            t = ds[i] / (ds[i] - ds[j])
            out.append([p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1]), p[2] + t * (q[2] - p[2])])
    return out if len(out) >= 3 else None


def newell_area(w):
    ax = ay = az = 0.0
    count = len(w)
    for i in range(count):
        p = w[i]
        q = w[i + 1 if i + 1 < count else 0]
        ax += (p[1] - q[1]) * (p[2] + q[2])
        ay += (p[2] - q[2]) * (p[0] + q[0])
        az += (p[0] - q[0]) * (p[1] + q[1])
    return 0.5 * math.sqrt(ax * ax + ay * ay + az * az)


def brush_faces(bsp, brush):
    """[(side shader index, polygon in map units)] for every side that yields a polygon."""
    first, count, _ = brush
    out = []
    for s in range(first, first + count):
        plane_num, shader = bsp.sides[s]
        p = bsp.planes[plane_num]
        w = base_winding(p[:3], p[3])
        for s2 in range(first, first + count):
            if s2 == s:
                continue
            plane2 = bsp.sides[s2][0]
            if plane2 == (plane_num ^ 1):
                continue
            q = bsp.planes[plane2]
            w = clip_back(w, q[:3], q[3])
            if w is None:
                break
        if w is None or newell_area(w) < MIN_AREA:
            continue
        out.append((shader, w))
    return out


def world_faces(bsp, stats):
    """[(side shader index, polygon)] of the solid brushes of model 0, in BSP order."""
    model = bsp.models[0]
    first, count = model[8], model[9]
    faces = []
    for b in range(first, first + count):
        brush = bsp.brushes[b]
        if not (bsp.shader(brush[2])[2] & CONTENTS_SOLID):
            stats["nonsolid_brushes"] += 1
            continue
        stats["solid_brushes"] += 1
        f = brush_faces(bsp, brush)
        if not f:
            stats["empty_brushes"] += 1
        faces.extend(f)
    return faces


# ---------------------------------------------------------------------------------------------
# Shader scripts (for the lit variant)
# ---------------------------------------------------------------------------------------------
def read_shader_scripts(pk3_dir):
    """{lower-case shader name: {"surfacelight": float or None, "lava": bool, "sky": bool}};
    pk3s in name order, later definitions override earlier ones."""
    result = {}
    for pk3 in sorted(glob.glob(os.path.join(pk3_dir, "*.pk3"))):
        try:
            z = zipfile.ZipFile(pk3)
        except (OSError, zipfile.BadZipFile):
            continue
        with z:
            for member in sorted(z.namelist()):
                low = member.lower()
                if not (low.startswith("scripts/") and low.endswith(".shader")):
                    continue
                text = z.read(member).decode("latin-1")
                result.update(parse_shader_text(text))
    return result


def parse_shader_text(text):
    text = re.sub(r"//[^\n]*", "", text)
    out = {}
    depth = 0
    name = None
    info = None
    for raw_line in text.split("\n"):
        # braces may share a line with other tokens
        for piece in re.split(r"([{}])", raw_line):
            piece = piece.strip()
            if not piece:
                continue
            if piece == "{":
                depth += 1
                if depth == 1 and name is not None:
                    info = {"surfacelight": None, "lava": False, "sky": False}
                continue
            if piece == "}":
                depth = max(0, depth - 1)
                if depth == 0 and name is not None and info is not None:
                    out[name] = info
                    name = None
                    info = None
                continue
            tokens = piece.split()
            if depth == 0:
                name = tokens[0].lower()
            elif depth == 1 and info is not None:
                key = tokens[0].lower()
                if key == "q3map_surfacelight" and len(tokens) > 1:
                    try:
                        info["surfacelight"] = float(tokens[1])
                    except ValueError:
                        pass
                elif key == "surfaceparm" and len(tokens) > 1:
                    if tokens[1].lower() == "lava":
                        info["lava"] = True
                    elif tokens[1].lower() == "sky":
                        info["sky"] = True
    return out


def texture_kd(name):
    """Grey-ish colour from the CRC-32 of the shader name: brightness from the low byte, a
    warm/cool tint from the next one."""
    h = zlib.crc32(name.encode("latin-1")) & 0xFFFFFFFF
    g = 0.3 + 0.4 * (h & 255) / 255.0
    tint = 0.1 - 0.2 * ((h >> 8) & 255) / 255.0
    return (g * (1.0 - tint), g, g * (1.0 + tint))


# ---------------------------------------------------------------------------------------------
# Light entities (for the lit variant)
# ---------------------------------------------------------------------------------------------
def parse_entities(text):
    ents = []
    for block in re.findall(r"\{([^{}]*)\}", text):
        ents.append({k.lower(): v for k, v in re.findall(r'"([^"]*)"\s+"([^"]*)"', block)})
    return ents


def numbers(s):
    out = []
    for tok in s.split():
        try:
            out.append(float(tok))
        except ValueError:
            return []
    return out


def solid_brush_planes(bsp):
    model = bsp.models[0]
    planes = []
    for b in range(model[8], model[8] + model[9]):
        first, count, shader = bsp.brushes[b]
        if bsp.shader(shader)[2] & CONTENTS_SOLID:
            planes.append([bsp.planes[bsp.sides[s][0]] for s in range(first, first + count)])
    return planes


def box_overlaps_brush(lo, hi, planes):
    """True when the open box (lo, hi) and the brush's interior may overlap (separating axes:
    the brush's planes; its own box is covered by its axial sides, which every BSP brush has)."""
    for p in planes:
        nx, ny, nz, d = p
        # the box corner furthest behind the plane
        x = lo[0] if nx > 0 else hi[0]
        y = lo[1] if ny > 0 else hi[1]
        z = lo[2] if nz > 0 else hi[2]
        if nx * x + ny * y + nz * z - d >= -1e-6:
            return False
    return True


def light_cubes(bsp, stats):
    """[(emission rgb, [polygons])] for the point lights, cubes in map units."""
    brushes = solid_brush_planes(bsp)
    out = []
    for e in parse_entities(bsp.entities):
        if e.get("classname", "").lower() != "light":
            continue
        o = numbers(e.get("origin", ""))
        if len(o) != 3:
            stats["lights_skipped"] += 1
            continue
        value = LIGHT_DEFAULT
        for key in ("light", "_light"):
            if key in e:
                v = numbers(e[key])
                if v:
                    value = v[0]
                break
        if value <= 0:
            stats["lights_skipped"] += 1
            continue
        colour = (1.0, 1.0, 1.0)
        c = numbers(e.get("_color", e.get("color", "")))
        if len(c) == 3 and min(c) >= 0 and max(c) > 0:
            m = max(c)
            colour = (c[0] / m, c[1] / m, c[2] / m)
        half = LIGHT_CUBE / 2
        while half >= 1.0:
            lo = (o[0] - half, o[1] - half, o[2] - half)
            hi = (o[0] + half, o[1] + half, o[2] + half)
            if not any(box_overlaps_brush(lo, hi, planes) for planes in brushes):
                break
            half /= 2
        if half < 1.0:
            stats["lights_skipped"] += 1
            continue
        if half < LIGHT_CUBE / 2:
            stats["lights_shrunk"] += 1
        size = 2 * half
        ke_scalar = LIGHT_POWER_PER_VALUE * value / (6 * size * size)
        emission = tuple(ke_scalar * ch for ch in colour)
        out.append((emission, cube_polygons(lo, hi)))
    return out


def cube_polygons(lo, hi):
    x0, y0, z0 = lo
    x1, y1, z1 = hi
    return [
        [[x0, y0, z0], [x0, y0, z1], [x0, y1, z1], [x0, y1, z0]],  # -x
        [[x1, y0, z0], [x1, y1, z0], [x1, y1, z1], [x1, y0, z1]],  # +x
        [[x0, y0, z0], [x1, y0, z0], [x1, y0, z1], [x0, y0, z1]],  # -y
        [[x0, y1, z0], [x0, y1, z1], [x1, y1, z1], [x1, y1, z0]],  # +y
        [[x0, y0, z0], [x0, y1, z0], [x1, y1, z0], [x1, y0, z0]],  # -z
        [[x0, y0, z1], [x1, y0, z1], [x1, y1, z1], [x0, y1, z1]],  # +z
    ]


# ---------------------------------------------------------------------------------------------
# Output
# ---------------------------------------------------------------------------------------------
def fmt_g(values):
    return " ".join("%g" % v for v in values)


def write_obj(path, header, mtl_name, faces):
    """faces: [(material, polygon in map units)]; consecutive faces share a usemtl line."""
    inv = 1.0 / SCALE
    lines = [header, "mtllib " + mtl_name]
    for _, w in faces:
        for p in w:
            lines.append("v %.6f %.6f %.6f" % (p[0] * inv, p[1] * inv, p[2] * inv))
    current = None
    k = 1
    for mat, w in faces:
        if mat != current:
            lines.append("usemtl " + mat)
            current = mat
        lines.append("f " + " ".join(str(k + i) for i in range(len(w))))
        k += len(w)
    with open(path, "w", newline="\n") as f:
        f.write("\n".join(lines) + "\n")


def convert(args):
    data, origin, map_name, pk3 = read_source(args.source)
    bsp = Bsp(data, args.source)
    base = args.name or map_name
    os.makedirs(args.outdir, exist_ok=True)
    stats = {"solid_brushes": 0, "nonsolid_brushes": 0, "empty_brushes": 0,
             "lights_skipped": 0, "lights_shrunk": 0}
    faces = world_faces(bsp, stats)
    if not faces:
        raise ValueError("%s: no solid brush face in the world model" % args.source)
    pk3_dir = args.pk3_dir or (os.path.dirname(os.path.abspath(pk3)) if pk3 else DEFAULT_PK3_DIR)
    scripts = read_shader_scripts(pk3_dir) if os.path.isdir(pk3_dir) else {}
    if not scripts:
        print("warning: no shader scripts found in %s: sky only from the BSP's surface flags, "
              "no glowing shaders" % pk3_dir, file=sys.stderr)

    def is_sky(shader_index):
        name, flags, _ = bsp.shader(shader_index)
        info = scripts.get(name.lower())
        return bool(flags & SURF_SKY) or bool(info and info["sky"])

    written = []
    if not args.lit or args.both:
        obj = os.path.join(args.outdir, base + ".obj")
        mtl = os.path.join(args.outdir, base + ".mtl")
        out = [("sky" if is_sky(sh) else "wall", w) for sh, w in faces]
        write_obj(obj, "# %s, %d polygons" % (origin, len(out)), base + ".mtl", out)
        with open(mtl, "w", newline="\n") as f:
            f.write("newmtl wall\nKd 0.6 0.6 0.6\nKe 0.0 0.0 0.0\n\n"
                    "newmtl sky\nKd 0.0 0.0 0.0\nKe 1.0 1.0 1.0\n\n")
        written.append((obj, len(out), "%d sky" % sum(1 for m, _ in out if m == "sky")))

    if args.lit or args.both:
        inv2 = 1.0 / (SCALE * SCALE)
        cubes = light_cubes(bsp, stats)
        # material and emission of every face
        tagged = []
        for sh, w in faces:
            name, flags, contents = bsp.shader(sh)
            info = scripts.get(name.lower())
            light = info["surfacelight"] if info else None
            if light is not None and light >= GLOW_MIN_SURFACELIGHT:
                if is_sky(sh):
                    ke = (0.0, 0.0, 0.0)  # the lit variants' sky does not emit
                elif contents & CONTENTS_LAVA or info["lava"]:
                    ke = LAVA_KE
                else:
                    ke = GLOW_KE
                tagged.append(["glow:" + name, (0.0, 0.0, 0.0), ke, w, sh])
            else:
                tagged.append(["q3:" + name, texture_kd(name), (0.0, 0.0, 0.0), w, sh])
        glow_faces = sum(1 for t in tagged if any(t[2]))
        sky_fallback = 0
        if glow_faces == 0 and not cubes:
            # Not in the references (they all have emitters): a level lit only by its sky (and
            # q3map_sun / ambient) would be dark; let its sky emit as in the plain variant.
            for t in tagged:
                if is_sky(t[4]):
                    t[0] = "glow:" + bsp.shader(t[4])[0]
                    t[1], t[2] = (0.0, 0.0, 0.0), (1.0, 1.0, 1.0)
                    sky_fallback += 1
            if sky_fallback == 0:
                print("warning: %s: no glowing shader, light entity or sky: the lit variant has "
                      "no emitter" % args.source, file=sys.stderr)
        materials = {}  # name -> (Kd, Ke), in order of first use
        out = []
        power = [0.0, 0.0, 0.0]
        for mat, kd, ke, w, _ in tagged:
            materials.setdefault(mat, (kd, ke))
            if any(ke):
                a = newell_area(w) * inv2
                for c in range(3):
                    power[c] += a * ke[c]
            out.append((mat, w))
        emitter_faces = 0
        light_mat = {}
        for emission, polys in cubes:
            key = tuple(round(c, 9) for c in emission)
            if key not in light_mat:
                light_mat[key] = "light_%d" % len(light_mat)
                materials[light_mat[key]] = ((0.0, 0.0, 0.0), emission)
            for w in polys:
                out.append((light_mat[key], w))
                emitter_faces += 1
                a = newell_area(w) * inv2
                for c in range(3):
                    power[c] += a * emission[c]
        obj = os.path.join(args.outdir, "lit-" + base + ".obj")
        mtl = os.path.join(args.outdir, "lit-" + base + ".mtl")
        what = "quake3: %d light entity cubes, %d glowing shader faces" % (len(cubes), glow_faces)
        if sky_fallback:
            what += ", no other emitter: %d sky faces emit" % sky_fallback
        header = ("# %s.obj with emitters from the level's own light information (%s); %d faces + "
                  "%d emitter faces; emitted power %s" % (base, what, len(faces), emitter_faces,
                                                         fmt_g(power)))
        write_obj(obj, header, "lit-" + base + ".mtl", out)
        with open(mtl, "w", newline="\n") as f:
            for name, (kd, ke) in materials.items():
                f.write("newmtl %s\nKd %s\nKe %s\n\n" % (name, fmt_g(kd), fmt_g(ke)))
        written.append((obj, len(out), what))

    for obj, n, what in written:
        print("%s: %d polygons (%s)" % (obj, n, what))
    print("  %d solid brushes (%d without any polygon), %d non-solid brushes skipped; light "
          "entities: %d skipped, %d with a smaller cube" % (
              stats["solid_brushes"], stats["empty_brushes"], stats["nonsolid_brushes"],
              stats["lights_skipped"], stats["lights_shrunk"]))


def main():
    ap = argparse.ArgumentParser(
        description="Quake 3 / OpenArena BSP (IBSP 46) -> OBJ + MTL brush soup (map units / 32, "
                    "z up), in the conventions of ../shared/data/levels/q3-*.obj.")
    ap.add_argument("source", help="a .bsp file, or PK3:maps/NAME.bsp")
    ap.add_argument("-o", "--outdir", default=".", help="output folder (default: .)")
    ap.add_argument("--name", help="output base name (default: the map's name)")
    ap.add_argument("--lit", action="store_true",
                    help="write the lit variant lit-NAME.obj/.mtl instead of the plain one")
    ap.add_argument("--both", action="store_true", help="write the plain and the lit variants")
    ap.add_argument("--pk3-dir", help="folder of the pk3s whose scripts/*.shader are read for "
                                      "--lit (default: the PK3's folder, else %s)" % DEFAULT_PK3_DIR)
    args = ap.parse_args()
    try:
        convert(args)
    except (ValueError, OSError, zipfile.BadZipFile, struct.error) as e:
        print("error: %s" % e, file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
