#!/usr/bin/env python3
"""Convert Doom-format levels (vanilla WAD maps, e.g. Freedoom) into Wavefront OBJ + MTL
"2.5D sector levels" with the conventions of ../shared/data/levels/doom-*.obj.

Usage:
  wad_to_obj.py WAD MAP [MAP ...] -o OUTDIR [--name NAME] [--both | --lit] [--seed N]
  wad_to_obj.py WAD --list

Conventions (see scripts/README.md for details):
- coordinates are map units / 32, z up; every face has its own vertices;
- one-sided linedefs give a wall quad from floor to ceiling facing into their sector; two-sided
  linedefs give a lower part (between the two floors, facing the lower floor) and an upper part
  (between the two ceilings, facing the higher ceiling); upper parts between two sky ceilings
  use material `sky`, everything else `wall`; walls come in linedef order, lower before upper;
- floors and ceilings are the map's own convex subsectors: the level's bounding box (vertices,
  padded by 64 map units) clipped by the node partition lines from the root down to the
  subsector, then by the subsector's own segs; one floor (facing up) and one ceiling (facing
  down) per subsector in subsector order, skipped for closed sectors (ceiling <= floor);
  ceilings are `sky` (F_SKY1), `lamp` (light >= 224) or `ceiling`;
- the lit variant adds small emitting panels under the ceilings of lit sectors (light >= 144).

Python 3, standard library only.
"""
import argparse
import math
import os
import random
import re
import struct
import sys

SKY_FLAT = 'F_SKY1'
SCALE = 1.0 / 32.0
BBOX_PAD = 64            # map units added around the vertex bounding box before clipping
LAMP_LIGHT = 224         # ceilings of sectors this bright are `lamp`
LIT_LIGHT = 144          # sectors this bright get emitting panels in the lit variant
PANEL_SIZES = (16, 8, 4, 2, 1)   # map units, largest first
PANEL_MARGIN = 0.02      # units (/32): panel corners must stay this far inside the subsector
PANEL_DROP = 0.1         # units: panel hangs this far under the ceiling (at most 5 % of height)
AREA_PER_PANEL = 50.0    # square units of floor per panel
LIGHT_COLOR = (1.0, 0.95, 0.85)
GAMMA = 2.2

PLAIN_MTL = """newmtl wall
Kd 0.6 0.6 0.6
Ke 0.0 0.0 0.0

newmtl floor
Kd 0.4 0.4 0.4
Ke 0.0 0.0 0.0

newmtl ceiling
Kd 0.7 0.7 0.7
Ke 0.0 0.0 0.0

newmtl lamp
Kd 0.7 0.7 0.7
Ke 1.0 1.0 1.0

newmtl sky
Kd 0.0 0.0 0.0
Ke 0.3 0.3 0.3

"""

# Lit variant: the base materials do not emit; listed in order of first use.
LIT_BASE_MTL = {
    'wall': ('0.6 0.55 0.5', '0 0 0'),
    'sky': ('0 0 0', '0 0 0'),
    'floor': ('0.4 0.4 0.45', '0 0 0'),
    'lamp': ('0.7 0.7 0.7', '0 0 0'),
    'ceiling': ('0.7 0.7 0.7', '0 0 0'),
}

MAP_LUMPS = ('THINGS', 'LINEDEFS', 'SIDEDEFS', 'VERTEXES', 'SEGS', 'SSECTORS', 'NODES',
             'SECTORS', 'REJECT', 'BLOCKMAP', 'BEHAVIOR')
NO_SIDE = (-1, 0xFFFF)


class WadError(Exception):
    pass


# ---------------------------------------------------------------------------------------------
# WAD reading

def read_wad(path):
    with open(path, 'rb') as f:
        data = f.read()
    if len(data) < 12 or data[:4] not in (b'IWAD', b'PWAD'):
        raise WadError('%s: not a WAD file' % path)
    n, off = struct.unpack_from('<ii', data, 4)
    lumps = []
    for i in range(n):
        pos, size, name = struct.unpack_from('<ii8s', data, off + 16 * i)
        lumps.append((name.split(b'\0')[0].decode('latin-1').upper(), data[pos:pos + size]))
    return lumps


def map_names(lumps):
    names = []
    for i, (name, _) in enumerate(lumps):
        if i + 1 < len(lumps) and lumps[i + 1][0] == 'THINGS':
            names.append(name)
    return names


def get_map(lumps, mapname):
    mapname = mapname.upper()
    for i, (name, _) in enumerate(lumps):
        if name == mapname:
            m = {}
            for nm, data in lumps[i + 1:i + 1 + len(MAP_LUMPS)]:
                if nm not in MAP_LUMPS or nm in m:
                    break
                m[nm] = data
            for need in ('LINEDEFS', 'SIDEDEFS', 'VERTEXES', 'SEGS', 'SSECTORS', 'NODES',
                         'SECTORS'):
                if need not in m:
                    raise WadError('map %s has no %s lump' % (mapname, need))
            if 'BEHAVIOR' in m:
                raise WadError('map %s is in Hexen format (not supported)' % mapname)
            if m['NODES'][:4] in (b'XNOD', b'ZNOD', b'XGLN', b'ZGLN', b'XGL2', b'ZGL2'):
                raise WadError('map %s has extended (ZDoom) nodes (not supported)' % mapname)
            return m
    raise WadError('map %s not found' % mapname)


def _cstr(b):
    return b.split(b'\0')[0].decode('latin-1').upper()


def parse_map(m):
    lvl = {}
    d = m['VERTEXES']
    lvl['vertices'] = [struct.unpack_from('<hh', d, i) for i in range(0, len(d) - 3, 4)]
    d = m['LINEDEFS']
    # v1, v2, flags, special, tag, front sidedef, back sidedef
    lvl['lines'] = [struct.unpack_from('<HHhhhHH', d, i) for i in range(0, len(d) - 13, 14)]
    d = m['SIDEDEFS']
    lvl['sides'] = [struct.unpack_from('<h', d, i + 28)[0] for i in range(0, len(d) - 29, 30)]
    d = m['SECTORS']
    secs = []
    for i in range(0, len(d) - 25, 26):
        fl, ce, ft, ct, light, special, tag = struct.unpack_from('<hh8s8shhh', d, i)
        secs.append((fl, ce, _cstr(ft), _cstr(ct), light, special, tag))
    lvl['sectors'] = secs
    d = m['SEGS']
    # v1, v2, angle, linedef, direction (0: front side), offset
    lvl['segs'] = [struct.unpack_from('<HHhHhh', d, i) for i in range(0, len(d) - 11, 12)]
    d = m['SSECTORS']
    lvl['subsectors'] = [struct.unpack_from('<HH', d, i) for i in range(0, len(d) - 3, 4)]
    d = m['NODES']
    # x, y, dx, dy, bbox right (4), bbox left (4), right child, left child
    lvl['nodes'] = [struct.unpack_from('<hhhh8hHH', d, i) for i in range(0, len(d) - 27, 28)]
    return lvl


# ---------------------------------------------------------------------------------------------
# geometry

def clip_halfplane(poly, ox, oy, dx, dy, keep_right):
    """Sutherland-Hodgman clip of a convex polygon by the line through (ox, oy) with direction
    (dx, dy), keeping its right side (the Doom BSP front side) or its left side.  The exact
    floating-point form (side = a*x + b*y + c, points on the line kept, consecutive points within
    1e-9 merged) matches the reference files, vertex order included."""
    a, b, c = dy, -dx, dx * oy - dy * ox
    if not keep_right:
        a, b, c = -a, -b, -c
    n = len(poly)
    if n == 0:
        return poly
    side = [a * p[0] + b * p[1] + c for p in poly]
    out = []
    for i in range(n):
        p = poly[i]
        j = i + 1 if i + 1 < n else 0
        q = poly[j]
        sa = side[i]
        sb = side[j]
        ina = sa >= 0
        if ina:
            out.append(p)
        if ina != (sb >= 0):
            t = sa / (sa - sb)
            out.append((p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1])))
    res = []
    for q in out:
        if res and abs(q[0] - res[-1][0]) <= 1e-9 and abs(q[1] - res[-1][1]) <= 1e-9:
            continue
        res.append(q)
    while len(res) > 1 and abs(res[0][0] - res[-1][0]) <= 1e-9 and \
            abs(res[0][1] - res[-1][1]) <= 1e-9:
        res.pop()
    return res


def area2(poly):
    s = 0.0
    n = len(poly)
    for i in range(n):
        x0, y0 = poly[i]
        x1, y1 = poly[(i + 1) % n]
        s += x0 * y1 - x1 * y0
    return s


def centroid(poly):
    a = area2(poly)
    gx = gy = 0.0
    n = len(poly)
    for i in range(n):
        x0, y0 = poly[i]
        x1, y1 = poly[(i + 1) % n]
        cr = x0 * y1 - x1 * y0
        gx += (x0 + x1) * cr
        gy += (y0 + y1) * cr
    return gx / (3.0 * a), gy / (3.0 * a)


class Level:
    def __init__(self, lvl, notes):
        self.v = lvl['vertices']
        self.lines = lvl['lines']
        self.sides = lvl['sides']
        self.sectors = lvl['sectors']
        self.segs = lvl['segs']
        self.ssectors = lvl['subsectors']
        self.nodes = lvl['nodes']
        self.notes = notes

    def side_sector(self, sd):
        if sd in NO_SIDE or sd >= len(self.sides):
            return None
        s = self.sides[sd]
        if s < 0 or s >= len(self.sectors):
            return None
        return s

    # walls ------------------------------------------------------------------------------------
    def walls(self):
        faces = []
        V = self.v
        S = self.sectors
        zero_len = 0
        for l in self.lines:
            if l[0] >= len(V) or l[1] >= len(V):
                continue
            a = V[l[0]]
            b = V[l[1]]
            if a == b:
                zero_len += 1
                continue
            fs = self.side_sector(l[5])
            bs = self.side_sector(l[6])

            def quad(p0, p1, z0, z1, mat):
                if z1 <= z0:
                    return
                faces.append((mat, [(p0[0], p0[1], z0), (p1[0], p1[1], z0),
                                    (p1[0], p1[1], z1), (p0[0], p0[1], z1)]))
            if fs is None and bs is None:
                continue
            if fs is None or bs is None:
                if fs is None:      # only a back side: face that side
                    a, b, fs = b, a, bs
                quad(a, b, S[fs][0], S[fs][1], 'wall')
                continue
            f1, c1 = S[fs][0], S[fs][1]
            f2, c2 = S[bs][0], S[bs][1]
            if f1 < f2:
                quad(a, b, f1, f2, 'wall')
            elif f2 < f1:
                quad(b, a, f2, f1, 'wall')
            mat = 'sky' if S[fs][3] == SKY_FLAT and S[bs][3] == SKY_FLAT else 'wall'
            if c1 > c2:
                quad(a, b, c2, c1, mat)
            elif c2 > c1:
                quad(b, a, c1, c2, mat)
        if zero_len:
            self.notes.append('%d zero-length linedefs skipped' % zero_len)
        return faces

    # subsectors -------------------------------------------------------------------------------
    def subsector_polygons(self):
        """Yields (subsector index, sector index or None, polygon in map units)."""
        N = self.nodes
        if not N:
            # a single-subsector map has no nodes
            paths = {0: []}
        else:
            paths = {}
            stack = [(len(N) - 1, [])]
            while stack:
                n, path = stack.pop()
                nd = N[n]
                for keep_right, child in ((True, nd[12]), (False, nd[13])):
                    p = path + [(n, keep_right)]
                    if child & 0x8000:
                        paths[child & 0x7FFF] = p
                    elif child < len(N):
                        stack.append((child, p))
        xs = [v[0] for v in self.v]
        ys = [v[1] for v in self.v]
        x0, y0 = min(xs) - BBOX_PAD, min(ys) - BBOX_PAD
        x1, y1 = max(xs) + BBOX_PAD, max(ys) + BBOX_PAD
        box = [(float(x0), float(y0)), (float(x1), float(y0)),
               (float(x1), float(y1)), (float(x0), float(y1))]
        unreached = 0
        for ssi, (count, first) in enumerate(self.ssectors):
            if ssi not in paths:
                unreached += 1
                continue
            poly = box
            for n, keep_right in paths[ssi]:
                nd = N[n]
                poly = clip_halfplane(poly, nd[0], nd[1], nd[2], nd[3], keep_right)
            sector = None
            for j in range(first, first + count):
                if j >= len(self.segs):
                    break
                sg = self.segs[j]
                a = self.v[sg[0]]
                b = self.v[sg[1]]
                poly = clip_halfplane(poly, a[0], a[1], b[0] - a[0], b[1] - a[1], True)
                if sector is None and sg[3] < len(self.lines):
                    l = self.lines[sg[3]]
                    sector = self.side_sector(l[6] if sg[4] else l[5])
            yield ssi, sector, poly
        if unreached:
            self.notes.append('%d subsectors not reachable from the BSP root' % unreached)


def flats(level):
    """Floor/ceiling faces in subsector order, plus per-subsector info for the lit variant."""
    faces = []
    info = []
    S = level.sectors
    nodeg = nosec = closed = 0
    for ssi, sector, poly in level.subsector_polygons():
        if len(poly) < 3 or abs(area2(poly)) < 1e-9:
            nodeg += 1
            continue
        if sector is None:
            nosec += 1
            continue
        fz, cz, ft, ct, light = S[sector][:5]
        if cz <= fz:
            closed += 1
            continue
        faces.append(('floor', [(x, y, fz) for x, y in poly]))
        mat = 'sky' if ct == SKY_FLAT else ('lamp' if light >= LAMP_LIGHT else 'ceiling')
        faces.append((mat, [(x, y, cz) for x, y in reversed(poly)]))
        info.append((ssi, sector, poly))
    if nodeg:
        level.notes.append('%d degenerate subsectors (no area) skipped' % nodeg)
    if nosec:
        level.notes.append('%d subsectors without a sector skipped' % nosec)
    if closed:
        level.notes.append('%d subsectors of closed sectors (ceiling <= floor) skipped' % closed)
    return faces, info


# ---------------------------------------------------------------------------------------------
# lit variant

def panel_margin(poly, cx, cy, half):
    """Smallest signed distance (positive inside) of the square's corners to the polygon edges."""
    m = float('inf')
    n = len(poly)
    for dx, dy in ((-half, -half), (half, -half), (half, half), (-half, half)):
        x = cx + dx
        y = cy + dy
        for i in range(n):
            a = poly[i]
            b = poly[(i + 1) % n]
            ex = b[0] - a[0]
            ey = b[1] - a[1]
            ln = math.hypot(ex, ey)
            if ln < 1e-12:
                continue
            m = min(m, (ex * (y - a[1]) - ey * (x - a[0])) / ln)
    return m


def make_panels(level, info, mapname, seed):
    """Returns (panels, n_lit, n_dark, total power).  A panel is
    (sector, k, [4 vertices in units], Ke triple)."""
    S = level.sectors
    by_sector = {}
    for ssi, sector, poly in info:
        by_sector.setdefault(sector, []).append((ssi, poly))
    panels = []
    n_lit = n_dark = 0
    power_total = [0.0, 0.0, 0.0]
    for s in sorted(by_sector):
        fz, cz, ft, ct, light = S[s][:5]
        if light < LIT_LIGHT:
            n_dark += 1
            continue
        n_lit += 1
        subs = by_sector[s]
        areas = [abs(area2(p)) * 0.5 * SCALE * SCALE for _, p in subs]
        area = sum(areas)
        power = area * (min(light, 255) / 255.0) ** GAMMA
        n = max(1, int(math.ceil(area / AREA_PER_PANEL - 0.5)))
        # pick n distinct subsectors at random, weighted by area (the references' placement is
        # statistically the same; their random stream cannot be reproduced)
        rng = random.Random('%s:%d:%d' % (mapname, s, seed))
        pool = list(range(len(subs)))
        weights = list(areas)
        chosen = []
        while pool and len(chosen) < n:
            r = rng.random() * sum(weights)
            acc = 0.0
            k = len(pool) - 1
            for i, w in enumerate(weights):
                acc += w
                if r < acc:
                    k = i
                    break
            chosen.append(pool.pop(k))
            weights.pop(k)
        height = (cz - fz) * SCALE
        placed = []
        for i in chosen:
            ssi, poly = subs[i]
            cx, cy = centroid(poly)
            for size in PANEL_SIZES:
                if size * SCALE > 0.5 * height:
                    continue
                if panel_margin(poly, cx, cy, size / 2.0) * SCALE >= PANEL_MARGIN:
                    placed.append((cx * SCALE, cy * SCALE, size * SCALE))
                    break
        if not placed:
            continue
        z = cz * SCALE - min(PANEL_DROP, 0.05 * height)
        for k, (x, y, size) in enumerate(placed):
            h = size / 2.0
            ke = power / (len(placed) * size * size)
            verts = [(x - h, y - h, z), (x - h, y + h, z), (x + h, y + h, z), (x + h, y - h, z)]
            panels.append((s, k, verts, tuple(ke * c for c in LIGHT_COLOR)))
        for i in range(3):
            power_total[i] += power * LIGHT_COLOR[i]
    return panels, n_lit, n_dark, power_total


# ---------------------------------------------------------------------------------------------
# output

def fmt_v(x, y, z):
    return 'v %.6f %.6f %.6f\n' % (x, y, z)


def write_obj(path, header, mtlname, faces, extra=()):
    """faces: (material, vertices in units); extra: (material, vertices) appended after."""
    out = [header, 'mtllib %s\n' % mtlname]
    allf = list(faces) + list(extra)
    for _, verts in allf:
        for x, y, z in verts:
            out.append(fmt_v(x, y, z))
    idx = 1
    cur = None
    for mat, verts in allf:
        if mat != cur:
            out.append('usemtl %s\n' % mat)
            cur = mat
        out.append('f ' + ' '.join(str(idx + i) for i in range(len(verts))) + '\n')
        idx += len(verts)
    with open(path, 'w') as f:
        f.write(''.join(out))


def convert(wad_path, lumps, mapname, outdir, name, want_plain, want_lit, seed, quiet=False):
    level = Level(parse_map(get_map(lumps, mapname)), [])
    wall_faces = level.walls()
    flat_faces, info = flats(level)
    faces = [(m, [(x * SCALE, y * SCALE, z * SCALE) for x, y, z in P])
             for m, P in wall_faces + flat_faces]
    wadname = os.path.basename(wad_path)
    written = []
    if want_plain:
        obj = os.path.join(outdir, name + '.obj')
        write_obj(obj, '# %s from %s, %d polygons\n' % (mapname.upper(), wadname, len(faces)),
                  name + '.mtl', faces)
        with open(os.path.join(outdir, name + '.mtl'), 'w') as f:
            f.write(PLAIN_MTL)
        written.append((obj, len(faces)))
    if want_lit:
        panels, n_lit, n_dark, power = make_panels(level, info, mapname.upper(), seed)
        lit = 'lit-' + name
        header = ('# %s.obj with emitters from the level\'s own light information (doom: %d lit '
                  'sectors, %d dark (light < %d)); %d faces + %d emitter faces; emitted power '
                  '%g %g %g\n' % (name, n_lit, n_dark, LIT_LIGHT, len(faces), len(panels),
                                  power[0], power[1], power[2]))
        extra = [('light_s%d_%d' % (s, k), verts) for s, k, verts, _ in panels]
        write_obj(os.path.join(outdir, lit + '.obj'), header, lit + '.mtl', faces, extra)
        mtl = []
        seen = []
        for m, _ in faces:
            if m not in seen:
                seen.append(m)
        for m in seen:
            kd, ke = LIT_BASE_MTL[m]
            mtl.append('newmtl %s\nKd %s\nKe %s\n\n' % (m, kd, ke))
        for s, k, _, ke in panels:
            mtl.append('newmtl light_s%d_%d\nKd 0 0 0\nKe %g %g %g\n\n' % ((s, k) + ke))
        with open(os.path.join(outdir, lit + '.mtl'), 'w') as f:
            f.write(''.join(mtl))
        written.append((os.path.join(outdir, lit + '.obj'), len(faces) + len(panels)))
    if not quiet:
        for path, n in written:
            print('%s: %d polygons' % (path, n))
        for note in level.notes:
            print('  note (%s %s): %s' % (wadname, mapname.upper(), note))
    return written


def default_name(wad_path, mapname):
    stem = os.path.splitext(os.path.basename(wad_path))[0].lower()
    m = re.match(r'freedoom(\d)$', stem)
    if m:
        stem = 'fd' + m.group(1)
    return 'doom-%s-%s' % (stem, mapname.lower())


def main(argv=None):
    ap = argparse.ArgumentParser(
        description='Convert Doom-format WAD maps into OBJ + MTL 2.5D sector levels '
                    '(conventions of shared/data/levels/doom-*.obj).')
    ap.add_argument('wad', help='WAD file, e.g. /usr/share/games/doom/freedoom2.wad')
    ap.add_argument('maps', nargs='*', help='map names, e.g. MAP01 or E1M2')
    ap.add_argument('-o', '--outdir', default='.', help='output directory (default: .)')
    ap.add_argument('--name', help='output base name for a single map '
                                   '(default: doom-fd2-map01 style)')
    g = ap.add_mutually_exclusive_group()
    g.add_argument('--both', action='store_true', help='write plain and lit-* variants')
    g.add_argument('--lit', action='store_true', help='write only the lit-* variant')
    ap.add_argument('--seed', type=int, default=0,
                    help='seed for the placement of emitting panels (lit variant)')
    ap.add_argument('--list', action='store_true', help='list the maps in the WAD and exit')
    args = ap.parse_args(argv)
    try:
        lumps = read_wad(args.wad)
        if args.list:
            print(' '.join(map_names(lumps)))
            return 0
        if not args.maps:
            ap.error('no map given (use --list to see the maps)')
        if args.name and len(args.maps) > 1:
            ap.error('--name needs a single map')
        os.makedirs(args.outdir, exist_ok=True)
        for mp in args.maps:
            name = args.name or default_name(args.wad, mp)
            convert(args.wad, lumps, mp, args.outdir, name, not args.lit, args.lit or args.both,
                    args.seed)
    except (WadError, OSError) as e:
        print('wad_to_obj: %s' % e, file=sys.stderr)
        return 1
    return 0


if __name__ == '__main__':
    sys.exit(main())
