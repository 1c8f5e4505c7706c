// The data `globalvis view` embeds (JSON in script#gv-data), unpacked into arrays the viewer
// uses: patch polygons, their pairs (visibility.txt) and per-patch adjacency.

/** Reads and checks the embedded JSON; throws with a clear message when it is missing. */
export function readEmbeddedData(doc) {
  const el = doc.getElementById('gv-data');
  if (!el) throw new Error('globalvis viewer: no embedded data (script#gv-data) in the page');
  const data = JSON.parse(el.textContent);
  if (data.format !== 'globalvis-viewer-1') {
    throw new Error(`globalvis viewer: unknown data format ${data.format}`);
  }
  return data;
}

/** Polygons stored as {sizes: [n0, n1, ...], xyz: [x, y, z, ...]}: vertex arrays per polygon. */
export function unpackPolygons(packed) {
  const polygons = [];
  let at = 0;
  for (const n of packed.sizes) {
    const vertices = [];
    for (let i = 0; i < n; ++i, at += 3) {
      vertices.push([packed.xyz[at], packed.xyz[at + 1], packed.xyz[at + 2]]);
    }
    polygons.push(vertices);
  }
  return polygons;
}

/** Mean of a polygon's vertices (a point inside it: patches are convex). */
export function centroid(vertices) {
  const c = [0, 0, 0];
  for (const v of vertices) for (let k = 0; k < 3; ++k) c[k] += v[k] / vertices.length;
  return c;
}

/** Unit normal of a convex polygon by Newell's method (front = counter-clockwise side). */
export function polygonNormal(vertices) {
  const n = [0, 0, 0];
  for (let i = 0; i < vertices.length; ++i) {
    const a = vertices[i];
    const b = vertices[(i + 1) % vertices.length];
    n[0] += (a[1] - b[1]) * (a[2] + b[2]);
    n[1] += (a[2] - b[2]) * (a[0] + b[0]);
    n[2] += (a[0] - b[0]) * (a[1] + b[1]);
  }
  const len = Math.hypot(n[0], n[1], n[2]) || 1;
  return [n[0] / len, n[1] / len, n[2] / len];
}

/**
 * The interactions of visibility.txt: pair k = (s[k], r[k]) with blockers
 * blockers[offset[k] .. offset[k+1]); an empty list is VISIBLE, otherwise PARTIAL.
 * `byPatch[p]` lists the pair indices that involve patch p.
 */
export function unpackPairs(packed, patchCount) {
  const count = packed ? packed.s.length : 0;
  const offset = new Uint32Array(count + 1);
  for (let k = 0; k < count; ++k) offset[k + 1] = offset[k] + packed.blockerCounts[k];
  const byPatch = Array.from({ length: patchCount }, () => []);
  for (let k = 0; k < count; ++k) {
    byPatch[packed.s[k]].push(k);
    byPatch[packed.r[k]].push(k);
  }
  return {
    count,
    s: packed ? packed.s : [],
    r: packed ? packed.r : [],
    /** False when the page was written without the lists (too many): counts only. */
    blockersEmbedded: !packed || packed.blockersEmbedded !== false,
    blockerCount(k) {
      return offset[k + 1] - offset[k];
    },
    /** The blockers of pair k ([] when the lists are not embedded). */
    blockersOf(k) {
      return this.blockersEmbedded ? packed.blockers.slice(offset[k], offset[k + 1]) : [];
    },
    isVisible(k) {
      return offset[k + 1] === offset[k];
    },
    partnerOf(k, p) {
      return packed.s[k] === p ? packed.r[k] : packed.s[k];
    },
    find(a, b) {
      for (const k of byPatch[a] || []) if (this.partnerOf(k, a) === b) return k;
      return -1;
    },
    byPatch,
  };
}

/**
 * The scene's up axis (0 = x, 1 = y, 2 = z): the axis opposite to which the emitters face on
 * the whole (ceiling lights face down), when that is clear; else z, the project's convention.
 */
export function upAxis(polygons, isEmitter) {
  const sum = [0, 0, 0];
  let count = 0;
  polygons.forEach((p, i) => {
    if (!isEmitter(i)) return;
    const n = polygonNormal(p);
    for (let k = 0; k < 3; ++k) sum[k] += n[k];
    count += 1;
  });
  if (count === 0) return 2;
  let best = 2;
  for (let k = 0; k < 3; ++k) if (Math.abs(sum[k]) > Math.abs(sum[best])) best = k;
  // Only a clear majority facing down along one axis decides.
  return sum[best] < -0.5 * count ? best : 2;
}
