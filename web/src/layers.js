// The viewer's three.js objects: surfaces shaded by radiosity or material colour, cells,
// portals and VISIBLE/PARTIAL links (the paper's Fig. 14 and §7.5 colours).
import * as THREE from 'three';
import { centroid, polygonNormal, unpackPolygons } from './scene_data.js';

/** Colours of the paper's figures (§7.4, §7.5) and of the viewer's own overlays. */
export const COLORS = {
  background: 0x1e2226,
  visibleLink: 0xffffff,
  partialLink: 0x22dd22,
  tube: 0xff2020,
  blocker: 0xff9900,
  source: 0xffee00,
  receiver: 0x00d0ff,
  cell: 0x4aa3ff,
  portal: 0xff40ff,
};

/** Gamma of the display encoding applied to linear colours (matches elements.ply's). */
const DISPLAY_GAMMA = 2.2;
/** Fraction of the patch area (by radiosity) below the value that maps to white. */
const WHITE_PERCENTILE = 0.99;
/** Directional term of the material-colour shading: ambient + diffuse * |n . light|. */
const AMBIENT = 0.45;
const LIGHT_DIRECTION = new THREE.Vector3(0.35, 0.55, 0.76).normalize();

function toDisplay(x) {
  return Math.pow(Math.min(Math.max(x, 0), 1), 1 / DISPLAY_GAMMA);
}

/** Fan-triangulated mesh of convex polygons with one display colour per polygon. */
function polygonMesh(polygons, colorOf, material) {
  let triangles = 0;
  for (const p of polygons) triangles += Math.max(p.length - 2, 0);
  const position = new Float32Array(triangles * 9);
  const color = new Float32Array(triangles * 9);
  const polygonOfTriangle = new Uint32Array(triangles);
  let t = 0;
  polygons.forEach((p, index) => {
    const c = colorOf(index, p);
    for (let i = 1; i + 1 < p.length; ++i, ++t) {
      const corners = [p[0], p[i], p[i + 1]];
      for (let j = 0; j < 3; ++j) {
        position.set(corners[j], t * 9 + j * 3);
        color.set(c, t * 9 + j * 3);
      }
      polygonOfTriangle[t] = index;
    }
  });
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute('position', new THREE.BufferAttribute(position, 3));
  geometry.setAttribute('color', new THREE.BufferAttribute(color, 3));
  const mesh = new THREE.Mesh(geometry, material);
  mesh.userData.polygonOfTriangle = polygonOfTriangle;
  return mesh;
}

/** Line segments along every edge of the polygons. */
function polygonEdges(polygons, color, clippingPlanes) {
  const points = [];
  for (const p of polygons) {
    for (let i = 0; i < p.length; ++i) points.push(...p[i], ...p[(i + 1) % p.length]);
  }
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute('position', new THREE.Float32BufferAttribute(points, 3));
  return new THREE.LineSegments(
    geometry,
    new THREE.LineBasicMaterial({ color, clippingPlanes, transparent: true, opacity: 0.7 }),
  );
}

/** Segments between the centroids of the patches of the pairs `ks`. */
export function linkSegments(ks, pairs, centroids, color) {
  const points = new Float32Array(ks.length * 6);
  ks.forEach((k, i) => {
    points.set(centroids[pairs.s[k]], i * 6);
    points.set(centroids[pairs.r[k]], i * 6 + 3);
  });
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute('position', new THREE.BufferAttribute(points, 3));
  return new THREE.LineSegments(
    geometry,
    new THREE.LineBasicMaterial({ color, transparent: true, opacity: 0.55, depthWrite: false }),
  );
}

/** Per-patch radiosity (linear RGB) to display colours, white at the area percentile. */
function patchRadiosityColors(radiosity, polygons) {
  const entries = polygons.map((p, i) => {
    const v = Math.max(radiosity[3 * i], radiosity[3 * i + 1], radiosity[3 * i + 2]);
    const n = polygonNormal(p);
    let area = 0;
    for (let j = 1; j + 1 < p.length; ++j) {
      const a = new THREE.Vector3(...p[j]).sub(new THREE.Vector3(...p[0]));
      const b = new THREE.Vector3(...p[j + 1]).sub(new THREE.Vector3(...p[0]));
      area += Math.abs(a.cross(b).dot(new THREE.Vector3(...n))) / 2;
    }
    return [v, area];
  });
  const sorted = [...entries].sort((a, b) => a[0] - b[0]);
  const total = sorted.reduce((s, e) => s + e[1], 0);
  let seen = 0;
  let white = 1;
  for (const [v, a] of sorted) {
    seen += a;
    white = v;
    if (seen >= WHITE_PERCENTILE * total) break;
  }
  if (!(white > 0)) white = 1;
  return (i) => [0, 1, 2].map((c) => toDisplay(radiosity[3 * i + c] / white));
}

/** The elements.ply mesh (leaf elements, display colours per vertex) as one mesh. */
function elementMesh(elements, material) {
  let triangles = 0;
  for (const n of elements.faceSizes) triangles += Math.max(n - 2, 0);
  const index = new Uint32Array(triangles * 3);
  let at = 0;
  let t = 0;
  for (const n of elements.faceSizes) {
    for (let i = 1; i + 1 < n; ++i, ++t) {
      index[3 * t] = elements.faceIndices[at];
      index[3 * t + 1] = elements.faceIndices[at + i];
      index[3 * t + 2] = elements.faceIndices[at + i + 1];
    }
    at += n;
  }
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute('position', new THREE.Float32BufferAttribute(elements.xyz, 3));
  geometry.setAttribute(
    'color',
    new THREE.Float32BufferAttribute(elements.rgb.map((c) => c / 255), 3),
  );
  geometry.setIndex(new THREE.BufferAttribute(index, 1));
  return new THREE.Mesh(geometry, material);
}

/**
 * Everything drawn from the data: `surfaces.radiosity` (elements or per-patch radiosity, if
 * the data has them), `surfaces.material`, `pick` (the patch mesh used for picking), `cells`,
 * `portals`, `visibleLinks`, `partialLinks`. `clippingPlanes` cut surfaces and cells.
 */
export function buildLayers(data, pairs, clippingPlanes) {
  const patches = unpackPolygons(data.patches);
  const centroids = patches.map(centroid);
  const normals = patches.map(polygonNormal);
  const surfaceMaterial = () =>
    new THREE.MeshBasicMaterial({ vertexColors: true, side: THREE.FrontSide, clippingPlanes });

  const materialColor = (i) => {
    const m = data.materials[data.patches.material[i]] || { kd: [0.5, 0.5, 0.5], ke: [0, 0, 0] };
    if (Math.max(...m.ke) > 0) return [1, 1, 0.85];
    const shade = AMBIENT + (1 - AMBIENT) * Math.abs(LIGHT_DIRECTION.dot(new THREE.Vector3(...normals[i])));
    return m.kd.map((c) => toDisplay(c * shade));
  };
  const materialMesh = polygonMesh(patches, materialColor, surfaceMaterial());

  let radiosityMesh = null;
  if (data.elements) {
    radiosityMesh = elementMesh(data.elements, surfaceMaterial());
  } else if (data.radiosity) {
    radiosityMesh = polygonMesh(patches, patchRadiosityColors(data.radiosity, patches), surfaceMaterial());
  }

  const layers = {
    patches,
    centroids,
    normals,
    surfaces: { material: materialMesh, radiosity: radiosityMesh },
    pick: materialMesh,
    cells: null,
    portals: null,
    visibleLinks: null,
    partialLinks: null,
  };
  if (data.cells) layers.cells = polygonEdges(unpackPolygons(data.cells), COLORS.cell, clippingPlanes);
  if (data.portals) {
    const polygons = unpackPolygons(data.portals);
    const group = new THREE.Group();
    const fill = new THREE.MeshBasicMaterial({
      color: COLORS.portal,
      transparent: true,
      opacity: 0.3,
      side: THREE.DoubleSide,
      depthWrite: false,
      clippingPlanes,
    });
    group.add(polygonMesh(polygons, () => [1, 1, 1], fill));
    group.add(polygonEdges(polygons, COLORS.portal, clippingPlanes));
    layers.portals = group;
  }
  const visible = [];
  const partial = [];
  for (let k = 0; k < pairs.count; ++k) (pairs.isVisible(k) ? visible : partial).push(k);
  layers.visibleLinks = linkSegments(visible, pairs, centroids, COLORS.visibleLink);
  layers.partialLinks = linkSegments(partial, pairs, centroids, COLORS.partialLink);
  return layers;
}
