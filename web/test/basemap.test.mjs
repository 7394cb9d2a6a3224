// SPDX-License-Identifier: MIT
// The basemap's drawing (web/src/basemap.js): each tile's two affine transforms put its corners
// where the server placed them, and the note says why nothing is drawn.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { basemapNote, tileTransforms } from '../src/basemap.js';

// Where the affine transform [a, b, c, d, e, f] (canvas setTransform's) puts the image point p.
const apply = ([a, b, c, d, e, f], [x, y]) => [a * x + c * y + e, b * x + d * y + f];
const near = (p, q) => assert.ok(Math.hypot(p[0] - q[0], p[1] - q[1]) < 1e-9, `${p} is not ${q}`);

test('each triangle of a tile is exact at its three corners, on any quadrilateral', () => {
  // A tile turned and sheared a little, not a parallelogram (the fourth corner off by 3 pixels).
  const q = [[10, 20], [266, 25], [262, 280], [3, 279]];
  const { upper, lower } = tileTransforms(q, 256, 256);
  near(apply(upper, [0, 0]), q[0]);
  near(apply(upper, [256, 0]), q[1]);
  near(apply(upper, [256, 256]), q[2]);
  near(apply(lower, [0, 0]), q[0]);
  near(apply(lower, [256, 256]), q[2]);
  near(apply(lower, [0, 256]), q[3]);
  // Not one transform for both: the upper one misses the bottom left corner.
  assert.ok(Math.hypot(...apply(upper, [0, 256]).map((v, i) => v - q[3][i])) > 1);
});

test('a parallelogram has one transform, whatever the image size', () => {
  const q = [[0, 0], [512, 10], [502, 522], [-10, 512]];
  const { upper, lower } = tileTransforms(q, 512, 512);
  upper.forEach((v, i) => assert.ok(Math.abs(v - lower[i]) < 1e-12));
});

test('the note says why no basemap is drawn', () => {
  assert.match(basemapNote({ source: null, enabled: false, crs: null }), /--tiles/);
  const source = { kind: 'directory' };
  assert.equal(basemapNote({ source, enabled: false, crs: null }), '');
  assert.match(basemapNote({ source, enabled: true, crs: null }), /names no coordinate reference system/);
  assert.equal(basemapNote({ source, enabled: true, crs: 'EPSG:25832' }), '');
  assert.equal(basemapNote({ source, enabled: true, crs: 'EPSG:25832', error: 'Basemap: x' }), 'Basemap: x');
});
