// SPDX-License-Identifier: MIT
// What the map view shows of the network (src/network-picture.js): a vector window's layers or a
// window's image, one at a time, through a zoom into a vector window and out of it again.
//
//   node --test test/
import assert from 'node:assert/strict';
import { test } from 'node:test';
import { NetworkPicture } from '../src/network-picture.js';

// An image as the worker posts it, its bitmap counting its close() calls.
function image(level) {
  const bitmap = { closed: 0, close() { ++this.closed; } };
  return { image: bitmap, bounds: [0, 0, 1000, 1000], key: { mode: 'overview', level } };
}

test('leaving a vector window shows its layers alone until the next image, not an older image under them', () => {
  const picture = new NetworkPicture();
  const overview = image(-4);
  picture.showImage(overview);
  assert.equal(picture.image, overview);
  assert.deepEqual(picture.layers, []);

  // Zoomed into a vector window: its layers, and the overview's image no longer shown (nor held).
  const layers = ['pipes', 'manholes'];
  picture.showLayers(layers);
  assert.equal(picture.layers, layers);
  assert.equal(picture.image, null, 'an image shown under the vector layers');
  assert.equal(overview.image.closed, 1, "the overview's bitmap is released once");

  // Zoomed out again: the view asks for a detail window's image; until it comes the picture is the
  // vector layers alone (the overview of another level is not shown again under or beside them).
  assert.equal(picture.image, null, 'the older image of another level shown while the new one is drawn');
  assert.equal(picture.layers, layers);

  // The detail image comes: it replaces the layers.
  const detail = image(-2);
  picture.showImage(detail);
  assert.equal(picture.image, detail);
  assert.deepEqual(picture.layers, []);
  assert.equal(detail.image.closed, 0);
  assert.equal(overview.image.closed, 1);
});

test('a new image replaces the last and releases its bitmap; another map shows nothing', () => {
  const picture = new NetworkPicture();
  const first = image(-3), second = image(-3);
  picture.showImage(first);
  picture.showImage(second);
  assert.equal(picture.image, second);
  assert.equal(first.image.closed, 1);
  picture.clear();
  assert.equal(picture.image, null);
  assert.deepEqual(picture.layers, []);
  assert.equal(second.image.closed, 1);
  picture.clear();  // nothing left to release
  assert.equal(second.image.closed, 1);
});
