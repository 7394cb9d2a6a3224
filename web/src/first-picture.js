// SPDX-License-Identifier: MIT
// A map's first picture (first-view.js): the network drawn on a 2-D canvas at the view, as the map
// view's layers and the worker's image draw it (lod.js's widths, radii and colours), before deck.gl's
// WebGL layers are ready. Up to kDetailBudget pipes every pipe and manhole as the layers draw them;
// beyond, every pipe as a line one device pixel wide and only the exits, as lod.js's overview shows
// them. Plain canvas 2D: a few strokes and fills whatever the count (one path per colour and width).
import { kBlocked, kClassColor, kDetailBudget, kExitColor, kManholeColor, kOpenEnd, manholeRadiusPx, pipeWidthPx } from './lod.js';

const kOverviewExitPx = 2.5;  // as lod.js's overview draws exits

// The network (lod.js's mapColumns; each pipe's class, or null: classed by their open ends) drawn
// on a 2-D context of width x height device pixels, for the view {target, zoom} (2^zoom CSS pixels
// a metre) at `dpr` device pixels a CSS pixel. Returns what it drew: {pipes, manholes, detail}.
export function drawNetwork(g, columns, classes, view, width, height, dpr) {
  const s = 2 ** view.zoom * dpr;
  const cx = view.target[0], cy = view.target[1];
  const px = (x) => (x - cx) * s + width / 2, py = (y) => (cy - y) * s + height / 2;
  const e = columns.ends, n = columns.diameters.length, m = columns.exits.length;
  const detail = n <= kDetailBudget;
  g.clearRect(0, 0, width, height);
  g.lineCap = 'round';
  // One path per colour and width: a few strokes whatever the count.
  const paths = new Map();
  let pipes = 0;
  for (let i = 0; i < n; ++i) {
    if (Number.isNaN(e[4 * i])) continue;  // a pipe with no position (geometry.js)
    ++pipes;
    const cls = classes ? classes[i] : columns.openEnd[i] ? kOpenEnd : 0;
    const w = detail ? Math.max(0.5, Math.round(2 * pipeWidthPx(columns.diameters[i]) * dpr) / 2) : dpr;
    const k = cls * 1e4 + w;
    let p = paths.get(k);
    if (!p) paths.set(k, (p = { cls, w, path: new Path2D() }));
    p.path.moveTo(px(e[4 * i]), py(e[4 * i + 1]));
    p.path.lineTo(px(e[4 * i + 2]), py(e[4 * i + 3]));
  }
  // Blocked pipes over the others, as the layers and the worker's image draw them.
  for (const p of [...paths.values()].sort((a, b) => (a.cls === kBlocked) - (b.cls === kBlocked))) {
    g.strokeStyle = rgb(kClassColor[p.cls]);
    g.lineWidth = p.w;
    g.stroke(p.path);
  }
  const fills = new Map();
  let manholes = 0;
  for (let j = 0; j < m; ++j) {
    const exit = columns.exits[j];
    if (!detail && !exit) continue;
    const r = (detail ? manholeRadiusPx(exit, columns.slots[j]) : kOverviewExitPx) * dpr;
    const k = exit * 1e4 + r;
    let f = fills.get(k);
    if (!f) fills.set(k, (f = { color: exit ? kExitColor : kManholeColor, path: new Path2D() }));
    const x = px(columns.positions[2 * j]), y = py(columns.positions[2 * j + 1]);
    f.path.moveTo(x + r, y);
    f.path.arc(x, y, r, 0, 2 * Math.PI);
    ++manholes;
  }
  for (const f of fills.values()) {
    g.fillStyle = rgb(f.color);
    g.fill(f.path);
  }
  return { pipes, manholes, detail };
}

const rgb = (c) => `rgb(${c[0]},${c[1]},${c[2]})`;
