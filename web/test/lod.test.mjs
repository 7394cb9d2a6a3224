// SPDX-License-Identifier: MIT
// The map view's level of detail (src/lod.js) in plain node, no browser: the grid's queries against
// a brute-force scan, picking, how a window is drawn (vector, detail, overview) and when it is
// rebuilt. The drawing itself (the worker's image) is checked by the browser test (e2e/).
//
//   node --test test/
import assert from 'node:assert/strict';
import { test } from 'node:test';
import { loadGeometry, placePoint, readGeometry } from '../src/geometry.js';
import { GridIndex, imageSize, kBlocked, keyServes, kNormal, kOpenEnd, kVectorBudget, lodKey, mapColumns, pick,
         pipeClasses, vectorData, WindowImage, workerColumns } from '../src/lod.js';

// A seeded street grid of `side` x `side` manholes 30 m apart (jittered by up to 10 m), each joined to
// its right neighbour and, every other column, to the one above; every 7th manhole an exit, and one
// pipe with an open end.
function gridDocument(side, seed = 1) {
  let s = seed;
  const rnd = () => (s = (s * 1103515245 + 12345) % 2147483648) / 2147483648;
  const g = { id: 'grid', name: 'grid', bounds: [0, 0, side * 30, side * 30],
              manholes: { name: [], x: [], y: [], slots: [], exit: [] },
              pipes: { name: [], from: [], to: [], length_m: [], diameter_m: [] }, points: [] };
  const m = g.manholes, p = g.pipes;
  for (let i = 0; i < side * side; ++i) {
    m.name.push(`M${i}`);
    m.x.push((i % side) * 30 + rnd() * 10);
    m.y.push(Math.floor(i / side) * 30 + rnd() * 10);
    m.slots.push(2 + (i % 3));
    m.exit.push(i % 7 === 0 ? 1 : 0);
  }
  const join = (a, b) => {
    p.name.push(`P${p.name.length}`);
    p.from.push(a);
    p.to.push(b);
    p.length_m.push(b < 0 ? 12 : Math.hypot(m.x[a] - m.x[b], m.y[a] - m.y[b]));
    p.diameter_m.push(0.2 + rnd() * 0.8);
  };
  for (let i = 0; i < side * side; ++i) {
    if (i % side + 1 < side) join(i, i + 1);
    if (i + side < side * side && i % 2 === 0) join(i, i + side);
  }
  join(0, -1);
  return g;
}
const gridMap = (side, seed = 1) => loadGeometry(gridDocument(side, seed));

const inRect = ([x0, y0, x1, y1], x, y) => x >= x0 && x <= x1 && y >= y0 && y <= y1;
// The view of a screen of 1000 x 800 CSS pixels centred on (x, y) at `zoom` (2^zoom pixels a metre),
// at a device pixel ratio.
const viewAt = (x, y, zoom, dpr = 1) => {
  const w = 500 * 2 ** -zoom, h = 400 * 2 ** -zoom;
  return { zoom, rect: [x - w, y - h, x + w, y + h], dpr };
};

test('the grid lists every pipe and manhole of a rectangle, each pipe once', () => {
  const map = gridMap(40);
  const index = new GridIndex(mapColumns(map));
  let s = 7;
  const rnd = () => (s = (s * 1103515245 + 12345) % 2147483648) / 2147483648;
  for (let k = 0; k < 50; ++k) {
    const x = rnd() * 1300 - 50, y = rnd() * 1300 - 50, rect = [x, y, x + rnd() * 400, y + rnd() * 400];
    const pipes = index.pipesIn(rect);
    assert.equal(new Set(pipes).size, pipes.length, 'a pipe listed twice');
    const listed = new Set(pipes);
    map.pipes.forEach((p, i) => {
      // A pipe whose bounding box meets the rectangle is listed (its cells meet the rectangle's).
      const meets = Math.min(p.from[0], p.to[0]) <= rect[2] && Math.max(p.from[0], p.to[0]) >= rect[0] &&
                    Math.min(p.from[1], p.to[1]) <= rect[3] && Math.max(p.from[1], p.to[1]) >= rect[1];
      if (meets) assert.ok(listed.has(i), `pipe ${p.name} meets ${rect} but is not listed`);
    });
    const manholes = new Set(index.manholesIn(rect));
    map.manholes.forEach((m, i) => {
      if (inRect(rect, ...m.position)) assert.ok(manholes.has(i), `manhole ${m.name} is in ${rect} but not listed`);
    });
    const counts = index.counts(rect);
    assert.ok(counts.pipes >= pipes.length && counts.manholes === manholes.size);
  }
});

test('a pick names the manhole under the pointer, else the pipe, and only what is drawn', () => {
  const map = gridMap(30);
  const index = new GridIndex(mapColumns(map));
  const zoom = 2;  // 4 pixels a metre: pipes 80 to 160 pixels long
  for (const [i, m] of map.manholes.entries()) {
    assert.deepEqual(pick(index, false, m.position, zoom), { kind: 'manhole', index: i });
  }
  for (const [i, p] of map.pipes.entries()) {
    if (p.openEnd) continue;
    const middle = [(p.from[0] + p.to[0]) / 2, (p.from[1] + p.to[1]) / 2];
    assert.deepEqual(pick(index, false, middle, zoom), { kind: 'pipe', index: i }, `the middle of ${p.name}`);
  }
  // Off the map, and between the rows of a street (15 m = 60 pixels from any pipe): nothing.
  assert.equal(pick(index, false, [-500, -500], zoom), null);
  const above = map.pipes.find((p) => p.name === 'P0');  // M0 to M1, with no pipe up from M1
  assert.equal(pick(index, false, [(above.from[0] + above.to[0]) / 2, above.from[1] + 17], zoom), null);
  // In the overview only exits are drawn: on a manhole that is no exit, a pipe (or nothing).
  const plain = map.manholes.findIndex((m) => !m.exit);
  assert.notEqual(pick(index, true, map.manholes[plain].position, zoom)?.kind, 'manhole');
  const exit = map.manholes.findIndex((m) => m.exit);
  assert.deepEqual(pick(index, true, map.manholes[exit].position, zoom), { kind: 'manhole', index: exit });
});

test('a window is drawn as layers when small, as an image beyond, merged beyond the detail budget', () => {
  const small = gridMap(4);
  const smallIndex = new GridIndex(mapColumns(small));
  assert.equal(lodKey(smallIndex, viewAt(45, 45, 0)).mode, 'vector');  // a small map, at any zoom
  assert.equal(lodKey(smallIndex, viewAt(45, 45, -6)).mode, 'vector');
  const big = gridMap(200);  // 40,000 manholes, 60,000 pipes
  const index = new GridIndex(mapColumns(big));
  const centre = [3000, 3000];
  assert.equal(lodKey(index, viewAt(...centre, -3)).mode, 'overview');     // the whole map
  assert.equal(lodKey(index, viewAt(...centre, -1)).mode, 'detail');       // about 5,000 pipes
  assert.equal(lodKey(index, viewAt(...centre, 2)).mode, 'vector');        // a few streets
  const key = lodKey(index, viewAt(...centre, 2));
  const n = index.counts(key.window);
  assert.ok(n.pipes + n.manholes <= kVectorBudget);
});

test('a window is rebuilt only when the view leaves it or the zoom rounds to another level', () => {
  const map = gridMap(100);
  const index = new GridIndex(mapColumns(map));
  const key = lodKey(index, viewAt(1500, 1500, 0));
  assert.ok(keyServes(key, viewAt(1500, 1500, 0)));
  assert.ok(keyServes(key, viewAt(1600, 1550, 0)), 'a pan of 100 pixels');
  assert.ok(keyServes(key, viewAt(1500, 1500, 0.4)), 'a zoom within the level');
  assert.ok(!keyServes(key, viewAt(1500, 1500, 0.6)), 'a zoom to the next level');
  assert.ok(!keyServes(key, viewAt(2500, 1500, 0)), 'a pan of a whole view');
  assert.ok(!keyServes(null, viewAt(1500, 1500, 0)));
  assert.ok(!keyServes(key, viewAt(1500, 1500, 0, 2)), 'the screen moved to a pixel ratio of 2');
  assert.equal(lodKey(index, viewAt(1500, 1500, 0, 2)).dpr, 2);
});

test("a window's image is as sharp as the screen: the level's zoom times the pixel ratio, within its caps", () => {
  const window = [0, 0, 1500, 1200];  // a screen of 1000 x 800 CSS pixels and its margins, at level 0
  assert.deepEqual(imageSize(window, 0, 1), { res: 1, scale: 1, width: 1500, height: 1200 });
  assert.deepEqual(imageSize(window, 0, 2), { res: 2, scale: 2, width: 3000, height: 2400 });
  assert.deepEqual(imageSize([0, 0, 375, 300], 2, 2), { res: 8, scale: 2, width: 3000, height: 2400 });
  assert.deepEqual(imageSize(window, 0), imageSize(window, 0, 1), 'no ratio given: 1');
  // At a ratio of 3 the image would be 4,500 x 3,600 (16 million pixels, 65 MB): it keeps to 12
  // million, with widths drawn as much thinner as the image is coarser.
  const three = imageSize(window, 0, 3);
  assert.ok(three.width * three.height <= 12e6 && three.width * three.height > 11.9e6, `${three.width}x${three.height}`);
  assert.ok(three.scale < 3 && three.scale > 2.5 && three.width === Math.round(1500 * three.res));
  // A long window keeps to 4,096 pixels a side.
  const long = imageSize([0, 0, 10000, 10], 0, 2);
  assert.equal(long.width, 4096);
  assert.equal(long.height, 4);
});

test("a vector window's layers hold its pipes and manholes, coloured by class", () => {
  const map = gridMap(6);
  const blocked = new Map([['P3', 'too narrow for makro-1.1']]);
  const classes = pipeClasses(map, blocked);
  assert.equal(classes[map.pipes.findIndex((p) => p.name === 'P3')], kBlocked);
  assert.equal(classes[map.pipes.findIndex((p) => p.openEnd)], kOpenEnd);
  assert.equal(classes[map.pipes.findIndex((p) => p.name === 'P0')], kNormal);
  const index = new GridIndex(mapColumns(map));
  const key = lodKey(index, viewAt(90, 90, 1));
  assert.equal(key.mode, 'vector');
  const data = vectorData(index, key, classes);
  assert.equal(data.pipes.length, map.pipes.length);
  assert.equal(data.manholes.length, map.manholes.length);
  const colors = data.pipes.attributes.getColor.value;
  const p3 = index.pipesIn(key.window).indexOf(map.pipes.findIndex((p) => p.name === 'P3'));
  assert.deepEqual([...colors.slice(4 * p3, 4 * p3 + 3)], [200, 40, 40]);
  const positions = data.manholes.attributes.getPosition.value;
  assert.ok(positions instanceof Float64Array, 'positions keep double precision');
});

// The server's compact geometry (server/src/map_geometry.h) of a JSON document, written here as
// map_geometry_binary writes it (format 2): little-endian sections after a 56-byte header.
function geometryBinary(g, { version = 2, magic = 'SPGM' } = {}) {
  const mh = g.manholes, pp = g.pipes, m = mh.name.length, p = pp.name.length;
  const names = new TextEncoder().encode([...mh.name, ...pp.name].join(''));
  const offsets = [0];
  for (const name of [...mh.name, ...pp.name]) offsets.push(offsets.at(-1) + new TextEncoder().encode(name).length);
  const size = 56 + 16 * m + 24 * p + 4 * (m + p + 1) + 3 * m + names.length;
  const buffer = new ArrayBuffer(size), v = new DataView(buffer);
  [...magic].forEach((c, k) => v.setUint8(k, c.charCodeAt(0)));
  v.setUint32(4, version, true); v.setUint32(8, m, true); v.setUint32(12, p, true);
  g.bounds.forEach((b, k) => v.setFloat64(16 + 8 * k, b, true));
  v.setUint32(48, names.length, true);
  let at = 56;
  const f64 = (x) => { v.setFloat64(at, x, true); at += 8; };
  const u32 = (x) => { v.setUint32(at, x, true); at += 4; };
  const u16 = (x) => { v.setUint16(at, x, true); at += 2; };
  const u8 = (x) => { v.setUint8(at, x); at += 1; };
  for (let i = 0; i < m; ++i) { f64(mh.x[i]); f64(mh.y[i]); }
  pp.length_m.forEach(f64); pp.diameter_m.forEach(f64);
  pp.from.forEach((a) => u32(a < 0 ? 0xffffffff : a)); pp.to.forEach((b) => u32(b < 0 ? 0xffffffff : b));
  offsets.forEach(u32); mh.slots.forEach(u16); mh.exit.forEach(u8);
  new Uint8Array(buffer, at).set(names);
  return buffer;
}

test('the compact geometry reads as the JSON: columns, open ends, names (not ASCII too)', () => {
  const g = gridDocument(6);
  g.manholes.name[3] = 'Schacht-Ü3';  // a name of more bytes than characters
  g.manholes.slots[4] = 300;          // more than a byte holds (format 1 cut it at 255)
  g.pipes.name[2] = 'Haltung-𝄞2';     // and one of two UTF-16 units for one character
  const json = loadGeometry(g), binary = readGeometry(geometryBinary(g), 'grid');
  assert.deepEqual(binary.columns, json.columns);
  assert.deepEqual(binary.openEnd, json.openEnd);
  assert.equal(binary.openEnd.reduce((a, b) => a + b, 0), 1);
  assert.deepEqual(binary.bounds, json.bounds);
  assert.deepEqual(binary.pipes, json.pipes);
  assert.deepEqual(binary.manholes, json.manholes);
  assert.equal(binary.manholeByName.get('Schacht-Ü3').i, 3);
  assert.equal(binary.manhole(4).slots, 300);
  assert.equal(json.manhole(4).slots, 300);
  assert.equal(binary.pipe(5).name, 'P5');
  // Looked up by name: every pipe's and manhole's index, the names after the wide ones too.
  g.pipes.name.forEach((name, i) => assert.equal(binary.pipeIndex(name), i));
  g.manholes.name.forEach((name, i) => assert.equal(binary.manholeByName.get(name).i, i));
  assert.equal(binary.pipeByName.get('Haltung-𝄞2').i, 2);
  assert.equal(binary.pipeIndex('P99'), undefined);
  assert.equal(binary.pipeByName.has('P99'), false);
  assert.equal(json.pipeIndex('Haltung-𝄞2'), 2);
  assert.throws(() => readGeometry(geometryBinary(g, { version: 1 }), 'grid'),
                /map 'grid' geometry: format 1, this page reads format 2: the page and the server are of different versions/);
  assert.throws(() => readGeometry(geometryBinary(g, { version: 3 }), 'grid'), /format 3, this page reads format 2/);
  assert.throws(() => readGeometry(geometryBinary(g, { magic: 'JSON' }), 'grid'), /not sewerplan geometry/);
  assert.throws(() => readGeometry(geometryBinary(g).slice(0, 200), 'grid'), /200 bytes for 36 manholes/);
});

test("the worker's columns are each its own buffer, the values the map's: nothing else is copied to it", () => {
  const g = gridDocument(6);
  const buffer = geometryBinary(g), map = readGeometry(buffer, 'grid');
  assert.equal(map.columns.positions.buffer, buffer, 'read in place, a view of the whole geometry');
  const { columns, transfer } = workerColumns(map);
  assert.deepEqual(Object.keys(columns).sort(), ['diameters', 'ends', 'exits', 'openEnd', 'positions', 'slots']);
  for (const [name, column] of Object.entries(columns)) {
    assert.equal(column.buffer.byteLength, column.byteLength, `${name} carries more than its own bytes`);
    assert.deepEqual(column, mapColumns(map)[name]);
    assert.ok(transfer.includes(column.buffer), `${name} is not transferred`);
  }
  assert.equal(transfer.length, 6);
});

// A 2-D canvas that records what is drawn (node has no OffscreenCanvas): each stroke's colour,
// width and lines, each image drawn.
class RecordingPath {
  constructor() { this.lines = []; this.arcs = 0; }
  moveTo(x, y) { this.at = [x, y]; }
  lineTo(x, y) { this.lines.push([...this.at, x, y]); }
  arc() { ++this.arcs; }
}
class RecordingCanvas {
  constructor(width, height) {
    Object.assign(this, { width, height, drawn: [], bitmaps: 0 });
    const drawn = this.drawn;
    this.context = {
      stroke(path) { drawn.push({ stroke: this.strokeStyle, width: this.lineWidth, lines: path.lines }); },
      fill(path) { drawn.push({ fill: this.fillStyle, circles: path.arcs }); },
      drawImage(image) { drawn.push({ image: image.layer }); },
    };
  }
  getContext() { return this.context; }
  transferToImageBitmap() { return { layer: this.bitmaps++, close() {} }; }
}

test("another profile's classes recolour a window's image: its layers blitted, only the blocked pipes stroked", () => {
  Object.assign(globalThis, { OffscreenCanvas: RecordingCanvas, Path2D: RecordingPath });
  try {
    const big = gridMap(200);
    const index = new GridIndex(mapColumns(big));
    // Two pipes in the middle of the windows below, far apart (not merged into one line).
    const [p, q] = [[300, 300], [420, 360]].map(([x, y]) => big.pipe(index.pipesIn([x, y, x + 1, y + 1])[0]).name);
    const blocked = new Map([[p, 'too narrow'], [q, 'too wide']]);
    const classes = pipeClasses(big, blocked);
    for (const [zoom, mode] of [[-1, 'detail'], [-3, 'overview']]) {
      const key = lodKey(index, viewAt(300, 300, zoom, 2));
      assert.equal(key.mode, mode);
      const image = new WindowImage(index, key);
      const size = imageSize(key.window, key.level, 2);
      assert.deepEqual([image.canvas.width, image.canvas.height], [size.width, size.height]);
      const layers = image.canvas.drawn.slice();  // the pipes' and manholes' layers
      assert.ok(layers.some((d) => d.stroke === 'rgb(60,90,160)') && layers.some((d) => d.fill), `${mode}: no pipes or manholes`);
      const red = image.canvas.drawn.filter((d) => d.stroke === 'rgb(200,40,40)');
      assert.equal(red.length, 0, 'a blocked pipe in the layers without a profile');
      image.canvas.drawn.length = 0;
      image.compose(classes);
      const drawn = image.canvas.drawn;
      assert.deepEqual(drawn[0], { image: 0 }, 'the pipes first');
      assert.deepEqual(drawn.at(-1), { image: 1 }, 'the manholes last');
      const strokes = drawn.slice(1, -1);
      assert.ok(strokes.every((d) => d.stroke === 'rgb(200,40,40)'), `${mode}: another colour repainted`);
      const lines = strokes.flatMap((d) => d.lines);
      assert.ok(lines.length === 2, `${mode}: ${lines.length} lines repainted for 2 blocked pipes`);
      if (mode === 'detail') assert.ok(strokes.every((d) => d.width >= 2), 'widths at the pixel ratio');
      image.canvas.drawn.length = 0;
      image.compose(pipeClasses(big, new Map()));
      assert.equal(image.canvas.drawn.length, 2, 'no profile: the two layers, nothing stroked');
    }
  } finally {
    delete globalThis.OffscreenCanvas;
    delete globalThis.Path2D;
  }
});

test('a name that starts with a byte-order mark keeps it, and every later name stays in place', () => {
  const g = gridDocument(3);
  g.manholes.name[0] = '\uFEFFM0';
  const map = readGeometry(geometryBinary(g), 'grid');
  assert.equal(map.manhole(0).name, '\uFEFFM0');
  g.manholes.name.forEach((name, i) => assert.equal(map.manholeByName.get(name).i, i));
  g.pipes.name.forEach((name, i) => assert.equal(map.pipeIndex(name), i));
});

test('a geometry whose pipe ends or name offsets are out of range is refused, naming the map', () => {
  const g = gridDocument(3);
  const bad = geometryBinary(g), v = new DataView(bad);
  const m = g.manholes.name.length, p = g.pipes.name.length;
  const fromAt = 56 + 16 * m + 16 * p;  // after positions, lengths and diameters
  v.setUint32(fromAt + 4, m, true);     // pipe 1 from manhole m: one past the last
  assert.throws(() => readGeometry(bad, 'grid'), /map 'grid' geometry: pipe 1's from is manhole 9, the map has 9 manholes/);
  const names = geometryBinary(g), w = new DataView(names);
  const offsetsAt = 56 + 16 * m + 24 * p;
  w.setUint32(offsetsAt + 4 * 2, 0, true);  // name 2 before name 1
  assert.throws(() => readGeometry(names, 'grid'), /name 2's offset 0 is before name 1's/);
});

test('a pipe with no manhole at either end has no position: listed, never drawn or picked', () => {
  const g = gridDocument(6);
  g.pipes.name.push('Stumpf');  // as a JSON map's "from": null, "to": null
  g.pipes.from.push(-1);
  g.pipes.to.push(-1);
  g.pipes.length_m.push(4.5);
  g.pipes.diameter_m.push(0.3);
  const stub = g.pipes.name.length - 1;
  for (const map of [loadGeometry(g), readGeometry(geometryBinary(g), 'grid')]) {
    assert.deepEqual([...map.placeless], [stub]);
    assert.equal(map.pipe(stub).placeless, true);
    assert.equal(map.pipe(0).placeless, false);
    assert.ok(map.pipe(stub).from.every(Number.isNaN));
    assert.equal(map.pipeIndex('Stumpf'), stub);  // still named: the page can list it
    assert.equal(placePoint(map, { pipe: 'Stumpf', offset_m: 1 }), null);
    const index = new GridIndex(mapColumns(map));
    assert.ok(Number.isFinite(index.x0) && Number.isFinite(index.cell), 'the grid spans the placed pipes only');
    const everywhere = [-1e9, -1e9, 1e9, 1e9];
    const listed = index.pipesIn(everywhere);
    assert.equal(listed.length, map.pipeCount - 1);
    assert.ok(!listed.includes(stub));
    // Where a stub at the bounds' lower corner was drawn before: the manhole there, not the pipe.
    const hit = pick(index, false, [g.bounds[0], g.bounds[1]], 2);
    assert.ok(!(hit?.kind === 'pipe' && hit.index === stub), 'the pipe is picked where it is not');
    const data = vectorData(index, { window: everywhere }, pipeClasses(map, new Map()));
    assert.ok(!data.pipes.attributes.getSourcePosition.value.some(Number.isNaN));
  }
});
