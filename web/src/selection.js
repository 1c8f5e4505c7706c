// What a selection draws: a patch with what it sees (partners tinted, its links), or one
// interaction with its tube (red) and blockers (orange), as the paper's Figs. 15-17 (§7.5).
import * as THREE from 'three';
import { ConvexGeometry } from 'three/addons/geometries/ConvexGeometry.js';
import { COLORS, linkSegments } from './layers.js';

/** Overlay offset along the patch normal, as a fraction of the scene diagonal (no z-fight). */
const OVERLAY_OFFSET = 2e-4;

function patchOverlay(layers, ids, color, opacity, offset, clippingPlanes) {
  const points = [];
  for (const id of ids) {
    const p = layers.patches[id];
    const n = layers.normals[id];
    const shifted = p.map((v) => [v[0] + n[0] * offset, v[1] + n[1] * offset, v[2] + n[2] * offset]);
    for (let i = 1; i + 1 < shifted.length; ++i) points.push(...shifted[0], ...shifted[i], ...shifted[i + 1]);
  }
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute('position', new THREE.Float32BufferAttribute(points, 3));
  const material = new THREE.MeshBasicMaterial({
    color,
    transparent: opacity < 1,
    opacity,
    side: THREE.DoubleSide,
    depthWrite: false,
    polygonOffset: true,
    polygonOffsetFactor: -2,
    polygonOffsetUnits: -2,
    clippingPlanes,
  });
  return new THREE.Mesh(geometry, material);
}

/**
 * Overlay for a selected patch `p`: itself (yellow), what it sees (VISIBLE partners white,
 * PARTIAL partners green) and its links in the same colours.
 */
export function patchSelectionGroup(layers, pairs, p, diagonal, clippingPlanes) {
  const group = new THREE.Group();
  const offset = OVERLAY_OFFSET * diagonal;
  const visible = [];
  const partial = [];
  for (const k of pairs.byPatch[p]) (pairs.isVisible(k) ? visible : partial).push(k);
  const partners = (ks) => ks.map((k) => pairs.partnerOf(k, p));
  group.add(patchOverlay(layers, partners(visible), COLORS.visibleLink, 0.35, offset, clippingPlanes));
  group.add(linkSegments(visible, pairs, layers.centroids, COLORS.visibleLink));
  group.add(patchOverlay(layers, partners(partial), COLORS.partialLink, 0.35, offset, clippingPlanes));
  group.add(linkSegments(partial, pairs, layers.centroids, COLORS.partialLink));
  group.add(patchOverlay(layers, [p], COLORS.source, 0.85, offset, clippingPlanes));
  return group;
}

/**
 * Overlay for the interaction k = (S, R): S and R, the tube (the segments between every vertex
 * of S and every vertex of R, and their convex hull, red) and the blockers (orange).
 */
export function pairSelectionGroup(layers, pairs, k, diagonal, clippingPlanes) {
  const group = new THREE.Group();
  const offset = OVERLAY_OFFSET * diagonal;
  const s = pairs.s[k];
  const r = pairs.r[k];
  const blockers = pairs.blockersOf(k);
  group.add(patchOverlay(layers, blockers, COLORS.blocker, 0.85, offset, clippingPlanes));
  group.add(patchOverlay(layers, [s], COLORS.source, 0.9, offset, clippingPlanes));
  group.add(patchOverlay(layers, [r], COLORS.receiver, 0.9, offset, clippingPlanes));

  const segments = [];
  for (const a of layers.patches[s]) for (const b of layers.patches[r]) segments.push(...a, ...b);
  const lines = new THREE.BufferGeometry();
  lines.setAttribute('position', new THREE.Float32BufferAttribute(segments, 3));
  group.add(new THREE.LineSegments(lines, new THREE.LineBasicMaterial({ color: COLORS.tube })));

  const hullPoints = [...layers.patches[s], ...layers.patches[r]].map((v) => new THREE.Vector3(...v));
  try {
    const hull = new ConvexGeometry(hullPoints);
    group.add(
      new THREE.Mesh(
        hull,
        new THREE.MeshBasicMaterial({
          color: COLORS.tube,
          transparent: true,
          opacity: 0.18,
          side: THREE.DoubleSide,
          depthWrite: false,
          // Hull faces lie in the planes of S and R: push them back so those win cleanly.
          polygonOffset: true,
          polygonOffsetFactor: 2,
          polygonOffsetUnits: 2,
        }),
      ),
    );
  } catch (e) {
    // Coplanar S and R have a flat hull: the segments alone show the tube.
  }
  return group;
}
