// SPDX-License-Identifier: MIT
// A map's first picture (src/first-picture.js), drawn on a recording 2-D context: every pipe and
// manhole where the view puts it, in the layers' widths, radii and colours, blocked pipes over the
// others; on a map beyond the detail budget every pipe thin and the exits only; a pipe with no
// position not drawn.
//
//   node --test test/
import assert from 'node:assert/strict';
import { test } from 'node:test';
import { drawNetwork } from '../src/first-picture.js';
import { kBlocked, kDetailBudget, kNormal, kOpenEnd, manholeRadiusPx, pipeWidthPx } from '../src/lod.js';

// Path2D as the context sees it: its segments and arcs.
globalThis.Path2D = class {
  constructor() { this.lines = []; this.arcs = []; this.at = null; }
  moveTo(x, y) { this.at = [x, y]; }
  lineTo(x, y) { this.lines.push([...this.at, x, y]); this.at = [x, y]; }
  arc(x, y, r) { this.arcs.push([x, y, r]); }
};

// A 2-D context that records each stroke and fill with its style.
function recorder() {
  const ops = [];
  return {
    ops,
    clearRect() { ops.push({ op: 'clear' }); },
    createImageData(width, height) { return { width, height, data: new Uint8ClampedArray(4 * width * height) }; },
    putImageData(image) { ops.push({ op: 'pixels', image }); },
    stroke(path) { ops.push({ op: 'stroke', color: this.strokeStyle, width: this.lineWidth, lines: path.lines }); },
    fill(path) { ops.push({ op: 'fill', color: this.fillStyle, arcs: path.arcs }); },
  };
}

// Columns of a map (lod.js's mapColumns): pipes from (x0, y0) to (x1, y1), manholes.
function columns(pipes, manholes) {
  return {
    ends: Float64Array.from(pipes.flatMap((p) => p.ends)),
    diameters: Float64Array.from(pipes, (p) => p.diameter),
    openEnd: Uint8Array.from(pipes, (p) => (p.open ? 1 : 0)),
    positions: Float64Array.from(manholes.flatMap((m) => m.at)),
    exits: Uint8Array.from(manholes, (m) => (m.exit ? 1 : 0)),
    slots: Uint16Array.from(manholes, (m) => m.slots ?? 2),
  };
}

test('each pipe and manhole where the view puts it, blocked pipes over the others', () => {
  const map = columns(
    [{ ends: [0, 0, 10, 0], diameter: 0.4 }, { ends: [10, 0, 10, 10], diameter: 0.4, open: true },
     { ends: [0, 0, 0, 10], diameter: 0.8 }, { ends: [NaN, NaN, NaN, NaN], diameter: 0.3 }],
    [{ at: [0, 0], exit: true }, { at: [10, 0], slots: 3 }, { at: [0, 10] }]);
  const g = recorder();
  // 4 CSS pixels a metre, device pixel ratio 2, the view's centre (5, 5) at the canvas's middle.
  const drawn = drawNetwork(g, map, Uint8Array.of(kNormal, kOpenEnd, kBlocked, kNormal),
                            { target: [5, 5], zoom: 2 }, 200, 100, 2);
  assert.deepEqual(drawn, { pipes: 3, manholes: 3, detail: true });
  // The worker's widths: at the device pixel ratio, to half pixels.
  const width = (d) => Math.round(2 * pipeWidthPx(d) * 2) / 2;
  const strokes = g.ops.filter((o) => o.op === 'stroke');
  const lines = strokes.flatMap((o) => o.lines.map((l) => [o.color, o.width, ...l]));
  // x: (x - 5) * 8 + 100, y: (5 - y) * 8 + 50 (y up on the map, down on the canvas).
  assert.deepEqual(lines.sort(), [
    ['rgb(140,140,140)', width(0.4), 140, 90, 140, 10],
    ['rgb(200,40,40)', width(0.8), 60, 90, 60, 10],
    ['rgb(60,90,160)', width(0.4), 60, 90, 140, 90],
  ].sort());
  assert.equal(strokes.at(-1).color, 'rgb(200,40,40)', 'the blocked pipe is not drawn over the others');
  const fills = g.ops.filter((o) => o.op === 'fill').flatMap((o) => o.arcs.map((a) => [o.color, ...a]));
  assert.deepEqual(fills.sort(), [
    ['rgb(20,150,60)', 60, 90, manholeRadiusPx(1, 2) * 2],
    ['rgb(90,90,90)', 140, 90, manholeRadiusPx(0, 3) * 2],
    ['rgb(90,90,90)', 60, 10, manholeRadiusPx(0, 2) * 2],
  ].sort());
  assert.ok(g.ops.findIndex((o) => o.op === 'fill') > g.ops.findLastIndex((o) => o.op === 'stroke'),
            'a pipe is drawn over the manholes');
});

test('without a profile yet, pipes are classed by their open ends', () => {
  const map = columns([{ ends: [0, 0, 1, 0], diameter: 0.4 }, { ends: [1, 0, 2, 0], diameter: 0.4, open: true }],
                      [{ at: [0, 0] }]);
  const g = recorder();
  drawNetwork(g, map, null, { target: [1, 0], zoom: 0 }, 10, 10, 1);
  assert.deepEqual(g.ops.filter((o) => o.op === 'stroke').map((o) => o.color).sort(), ['rgb(140,140,140)', 'rgb(60,90,160)']);
});

test('beyond the detail budget: every pipe one device pixel wide, blocked over the others, the exits only', () => {
  const n = kDetailBudget + 1;
  // Pipes along the x axis, one a metre: 1 pixel a metre at zoom 0 (dpr 1), pipe i from x = i to
  // i + 1; each tenth blocked; one more across them all, far outside the canvas at both ends.
  const pipes = Array.from({ length: n }, (_, i) => ({ ends: [i, 0, i + 1, 0], diameter: 0.4 }));
  pipes.push({ ends: [-1e9, -2, 1e9, -2], diameter: 0.4 });
  const classes = Uint8Array.from(pipes, (_, i) => (i % 10 === 0 ? kBlocked : kNormal));
  const manholes = Array.from({ length: 100 }, (_, i) => ({ at: [i, 0], exit: i % 10 === 0 }));
  const g = recorder();
  const width = 400, height = 20;
  const drawn = drawNetwork(g, columns(pipes, manholes), classes, { target: [width / 2, 0], zoom: 0 }, width, height, 1);
  assert.deepEqual(drawn, { pipes: n + 1, manholes: 10, detail: false });
  assert.equal(g.ops.filter((o) => o.op === 'stroke').length, 0, 'pipes stroked one by one');
  const { image } = g.ops.find((o) => o.op === 'pixels');
  const at = (x, y) => Array.from(image.data.subarray(4 * (y * width + x), 4 * (y * width + x) + 4));
  const blue = [60, 90, 160, 255], red = [200, 40, 40, 255], none = [0, 0, 0, 0];
  // y = 0 is the canvas's row 10; x = i is column i. Pixel 10 is the end of pipe 9 and the start of
  // pipe 10 (blocked): red over blue.
  assert.deepEqual(at(5, 10), blue);
  assert.deepEqual(at(10, 10), red);
  assert.deepEqual(at(15, 10), blue);
  assert.deepEqual(at(5, 11), none);
  assert.deepEqual(at(5, 9), none);
  // The long pipe at y = -2 (row 12), clipped to the canvas: every pixel of its row.
  for (let x = 0; x < width; ++x) assert.deepEqual(at(x, 12), blue);
  const fills = g.ops.filter((o) => o.op === 'fill');
  assert.deepEqual(fills.map((o) => [o.color, o.arcs.length]), [['rgb(20,150,60)', 10]]);
});
