// SPDX-License-Identifier: MIT
// The station's GIS habits in plain node, no browser: the names thinned so that none overlaps
// (src/labels.js), the scale bar's lengths (scale-bar.js), undo and redo (undo.js), a place found by
// name (search-box.js), and the mission kept across a reload, stale ones dropped (saved-mission.js).
// The browser test (e2e/gis-habits.mjs) checks them on the page.
//
//   node --test test/
import assert from 'node:assert/strict';
import { test } from 'node:test';
import { loadGeometry } from '../src/geometry.js';
import { thinLabels, kLabelHeightPx } from '../src/labels.js';
import { restoreMission, saveMission } from '../src/saved-mission.js';
import { scaleFor } from '../src/scale-bar.js';
import { findPlace, suggestions, viewOf } from '../src/search-box.js';
import { EditHistory } from '../src/undo.js';

// A street of `n` manholes `gap` m apart along x, joined by pipes P1..P(n-1), one exit.
function street(n, gap = 5) {
  const g = { id: 'street', name: 'street', bounds: [0, 0, (n - 1) * gap, 0],
              manholes: { name: [], x: [], y: [], slots: [], exit: [] },
              pipes: { name: [], from: [], to: [], length_m: [], diameter_m: [] }, points: [] };
  for (let i = 0; i < n; ++i) {
    g.manholes.name.push(`SW-${1000 + i}`);
    g.manholes.x.push(i * gap);
    g.manholes.y.push(i % 2);
    g.manholes.slots.push(2);
    g.manholes.exit.push(i === n - 1 ? 1 : 0);
  }
  for (let i = 1; i < n; ++i) {
    g.pipes.name.push(`P${i}`);
    g.pipes.from.push(i - 1);
    g.pipes.to.push(i);
    g.pipes.length_m.push(gap);
    g.pipes.diameter_m.push(0.4);
  }
  return loadGeometry(g);
}

const width = (name) => 7 * name.length;
const boxes = (kept, zoom) => kept.map((m) => {
  const s = 2 ** zoom, w = width(m.name), cx = m.position[0] * s, cy = m.position[1] * s;
  return [cx - w / 2, cy - kLabelHeightPx / 2, cx + w / 2, cy + kLabelHeightPx / 2];
});
const overlaps = (b) => b.some((p, i) => b.some((q, j) => i < j && p[0] < q[2] && q[0] < p[2] && p[1] < q[3] && q[1] < p[3]));

test('names close together are thinned so that no two overlap, exits first, more of them zoomed in', () => {
  const map = street(200);
  const all = map.manholes;
  assert.ok(overlaps(boxes(all, 2)), 'the street\'s names overlap unthinned (the test would not fail)');
  const counts = [];
  for (const zoom of [0, 2, 3, 4]) {
    const kept = thinLabels(all, zoom, width);
    assert.ok(!overlaps(boxes(kept, zoom)), `names overlap at zoom ${zoom}`);
    assert.equal(kept[0].name, 'SW-1199', 'the exit is named first');
    counts.push(kept.length);
  }
  assert.ok(counts.every((c, i) => i === 0 || c >= counts[i - 1]) && counts[0] < counts.at(-1), `counts ${counts}`);
  // Apart enough, every name is drawn; thinned at a zoom, none overlaps at a closer one either.
  assert.equal(thinLabels(all, 6, width).length, all.length);
  assert.ok(!overlaps(boxes(thinLabels(all, 2, width), 2.7)));
});

test('the scale bar is a round length no wider than its room', () => {
  for (const zoom of [-6, -2.3, 0, 1.5, 4, 7]) {
    const s = scaleFor(zoom, 160);
    assert.ok(s.px <= 160 && s.px > 160 / 5.1, `zoom ${zoom}: ${s.px} px`);
    assert.match(String(s.metres / 10 ** Math.floor(Math.log10(s.metres) + 1e-9)), /^[125]$/);
  }
  assert.deepEqual(scaleFor(0, 160), { metres: 100, px: 100, text: '100 m' });
  assert.equal(scaleFor(-4, 160).text, '2 km');
  assert.equal(scaleFor(8, 160).text, '50 cm');
});

test('undo and redo walk the recorded states; a new edit drops the redo list', () => {
  const h = new EditHistory(3);
  h.reset('a');
  assert.equal(h.record('a'), false);
  h.record('b');
  h.record('c');
  assert.equal(h.undo(), 'b');
  assert.equal(h.record('b'), false, 'the state restored is no new edit');
  assert.equal(h.redo(), 'c');
  assert.equal(h.undo(), 'b');
  h.record('d');
  assert.equal(h.canRedo, false);
  h.record('e');
  h.record('f');
  assert.deepEqual([h.undo(), h.undo(), h.undo(), h.undo()], ['e', 'd', 'b', null], 'at most 3 states back');
});

test('a place is found by its name, any case, or a beginning only one name has', () => {
  const map = street(30);
  assert.deepEqual(findPlace(map, 'SW-1003'), { kind: 'manhole', name: 'SW-1003', points: [[15, 1]] });
  assert.equal(findPlace(map, ' p7 ').name, 'P7');
  assert.deepEqual(findPlace(map, 'P7').points, [[30, 0], [35, 1]]);
  assert.equal(findPlace(map, 'sw-1029').name, 'SW-1029');
  assert.match(findPlace(map, 'SW-101').error, /^10 names begin with SW-101: SW-1010, SW-1011, .*, \.\.\.$/);
  assert.equal(findPlace(map, 'Q1').error, 'no manhole or pipe named Q1');
  assert.deepEqual(suggestions(map, 'p2'), ['P2', 'P20', 'P21', 'P22', 'P23', 'P24', 'P25', 'P26', 'P27', 'P28', 'P29']);
  const wide = street(30, 50);
  const v = viewOf(findPlace(wide, 'P7'), 900, 600);
  assert.deepEqual(v.target, [325, 0.5]);
  assert.ok(Math.abs(2 ** v.zoom * 150 - 600) < 1e-6, 'the pipe spans a third of the view');
  assert.equal(viewOf(findPlace(map, 'P7'), 900, 600).zoom, 4, 'a short pipe: 16 pixels a metre at most');
  assert.ok(Math.abs(2 ** viewOf(findPlace(wide, 'SW-1003'), 900, 600).zoom * 40 - 600) < 1e-6, '40 m around a manhole');
});

test('the mission is kept per map, and one saved for another map of the same ID is dropped with why', () => {
  const store = new Map();
  const storage = { getItem: (k) => store.get(k) ?? null, setItem: (k, v) => store.set(k, v), removeItem: (k) => store.delete(k) };
  const map = street(10);
  const mission = { format: 'sewerplan-mission', version: 1, name: 'm', profile: 'makro-plus',
                    start: { manhole: 'SW-1000' }, tasks: [{ name: 'inspect-1', type: 'inspect_pipe', pipe: 'P3' }] };
  assert.deepEqual(restoreMission(map, storage), { mission: null, message: '' });
  saveMission(map, mission, storage);
  assert.deepEqual(restoreMission(map, storage).mission, mission);
  const other = street(12);  // the same ID, another network
  const stale = restoreMission(other, storage);
  assert.equal(stale.mission, null);
  assert.match(stale.message, /^The mission saved for map street on .* was dropped: it was for another map of that ID \(10 manholes, 9 pipes; this one has 12 and 11\)$/);
  assert.equal(store.size, 0, 'the stale mission is forgotten');
  saveMission(map, { ...mission, tasks: [{ name: 'x', type: 'inspect_pipe', pipe: 'P99' }] }, storage);
  assert.match(restoreMission(map, storage).message, /it names pipe P99, which this map lacks$/);
  store.set('sewerplan-mission:street', '{not json');
  assert.match(restoreMission(map, storage).message, /it is not a readable mission$/);
});
