// Unit tests of the viewer's data helpers (web/src/scene_data.js) on hand-made cases:
// node --test web/test/scene_data_test.mjs
import assert from 'node:assert/strict';
import { test } from 'node:test';
import { centroid, polygonNormal, unpackPairs, unpackPolygons, upAxis } from '../src/scene_data.js';

// Two unit squares: one on z = 0 facing +z (counter-clockwise seen from above), one on z = 1
// facing -z (a ceiling light).
const floor = [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]];
const light = [[0, 0, 1], [0, 1, 1], [1, 1, 1], [1, 0, 1]];

test('polygons unpack in order with their vertices', () => {
  const packed = { sizes: [4, 3], xyz: [...floor.flat(), 0, 0, 5, 1, 0, 5, 0, 1, 5] };
  const polygons = unpackPolygons(packed);
  assert.equal(polygons.length, 2);
  assert.deepEqual(polygons[0], floor);
  assert.deepEqual(polygons[1][2], [0, 1, 5]);
});

test('normals follow the counter-clockwise front, centroids are the vertex means', () => {
  assert.deepEqual(polygonNormal(floor), [0, 0, 1]);
  assert.deepEqual(polygonNormal(light), [0, 0, -1]);
  assert.deepEqual(centroid(floor), [0.5, 0.5, 0]);
});

test('pairs: VISIBLE has no blockers, partners and lookups go both ways', () => {
  const pairs = unpackPairs({ s: [0, 0, 1], r: [1, 2, 2], blockerCounts: [0, 2, 1], blockers: [3, 4, 0] }, 5);
  assert.equal(pairs.count, 3);
  assert.equal(pairs.isVisible(0), true);
  assert.equal(pairs.isVisible(1), false);
  assert.deepEqual(pairs.blockersOf(1), [3, 4]);
  assert.deepEqual(pairs.blockersOf(2), [0]);
  assert.equal(pairs.blockerCount(1), 2);
  assert.deepEqual(pairs.byPatch[2], [1, 2]);
  assert.equal(pairs.partnerOf(2, 2), 1);
  assert.equal(pairs.find(2, 0), 1);
  assert.equal(pairs.find(0, 2), 1);
  assert.equal(pairs.find(3, 4), -1);
  assert.deepEqual(pairs.byPatch[4], []);
});

test('pairs without embedded blocker lists keep their counts', () => {
  const pairs = unpackPairs({ s: [0], r: [1], blockerCounts: [2], blockers: [], blockersEmbedded: false }, 2);
  assert.equal(pairs.isVisible(0), false);
  assert.equal(pairs.blockerCount(0), 2);
  assert.deepEqual(pairs.blockersOf(0), []);
  assert.equal(unpackPairs(null, 3).count, 0);
});

test('up axis: opposite to the way the lights face, z when unclear', () => {
  assert.equal(upAxis([floor, light], (i) => i === 1), 2);
  const yLight = [[0, 1, 0], [1, 1, 0], [1, 1, 1], [0, 1, 1]];  // faces -y
  assert.deepEqual(polygonNormal(yLight), [0, -1, 0]);
  assert.equal(upAxis([yLight], () => true), 1);
  assert.equal(upAxis([floor], () => true), 2);  // an emitter facing up decides nothing
  assert.equal(upAxis([floor], () => false), 2);  // no emitters
});
