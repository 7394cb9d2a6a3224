// SPDX-License-Identifier: MIT
// A map's first picture (first-view.js): the network drawn on a 2-D canvas at the view, as the map
// view's layers and the worker's image draw it (lod.js's widths, radii and colours), before deck.gl's
// WebGL layers are ready. Up to kDetailBudget pipes every pipe and manhole as the layers draw them;
// beyond, every pipe as a line one device pixel wide (written into the canvas's pixels) and only the
// exits, as lod.js's overview shows them. Plain canvas 2D, no WebGL.
import { kBlocked, kClassColor, kDetailBudget, kExitColor, kManholeColor, kNormal, kOpenEnd, manholeRadiusPx,
         pipeWidthPx } from './lod.js';

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
  const pipes = detail ? strokePipes(g, e, n, columns, classes, px, py, dpr)
    : rasterizePipes(g, e, n, columns, classes, px, py, width, height);
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
const classOf = (columns, classes, i) => (classes ? classes[i] : columns.openEnd[i] ? kOpenEnd : kNormal);

// Each pipe stroked in its width and colour: one path per colour and width, blocked pipes over the
// others, as the layers and the worker's image draw them. Returns the pipes drawn.
function strokePipes(g, e, n, columns, classes, px, py, dpr) {
  g.lineCap = 'round';
  const paths = new Map();
  let pipes = 0;
  for (let i = 0; i < n; ++i) {
    if (Number.isNaN(e[4 * i])) continue;  // a pipe with no position (geometry.js)
    ++pipes;
    const cls = classOf(columns, classes, i);
    const w = Math.max(0.5, Math.round(2 * pipeWidthPx(columns.diameters[i]) * dpr) / 2);
    const k = cls * 1e4 + w;
    let p = paths.get(k);
    if (!p) paths.set(k, (p = { cls, w, path: new Path2D() }));
    p.path.moveTo(px(e[4 * i]), py(e[4 * i + 1]));
    p.path.lineTo(px(e[4 * i + 2]), py(e[4 * i + 3]));
  }
  for (const p of [...paths.values()].sort((a, b) => (a.cls === kBlocked) - (b.cls === kBlocked))) {
    g.strokeStyle = rgb(kClassColor[p.cls]);
    g.lineWidth = p.w;
    g.stroke(p.path);
  }
  return pipes;
}

// Each pipe one device pixel wide, written into the canvas's pixels (a DDA along the part of the
// line inside the canvas), blocked pipes in a second pass over the others: O(pipes + pixels
// written). Stroking one path of the 100,000-manhole map's 109,000 pipes took the page's main
// thread 0.9 s (load 17); this is a pass over the columns. Returns the pipes drawn.
function rasterizePipes(g, e, n, columns, classes, px, py, width, height) {
  const image = g.createImageData(width, height);
  const data = image.data;
  let pipes = 0;
  for (const blockedPass of [false, true]) {
    for (let i = 0; i < n; ++i) {
      if (Number.isNaN(e[4 * i])) continue;  // a pipe with no position (geometry.js)
      const cls = classOf(columns, classes, i);
      if ((cls === kBlocked) !== blockedPass) continue;
      ++pipes;
      const line = clip(px(e[4 * i]), py(e[4 * i + 1]), px(e[4 * i + 2]), py(e[4 * i + 3]), width, height);
      if (!line) continue;
      const [x0, y0, x1, y1] = line;
      const [r, gr, b] = kClassColor[cls];
      const steps = Math.max(1, Math.ceil(Math.max(Math.abs(x1 - x0), Math.abs(y1 - y0))));
      for (let k = 0; k <= steps; ++k) {
        const x = Math.max(0, Math.min(width - 1, Math.floor(x0 + ((x1 - x0) * k) / steps)));
        const y = Math.max(0, Math.min(height - 1, Math.floor(y0 + ((y1 - y0) * k) / steps)));
        const o = 4 * (y * width + x);
        data[o] = r; data[o + 1] = gr; data[o + 2] = b; data[o + 3] = 255;
      }
    }
  }
  g.putImageData(image, 0, 0);
  return pipes;
}

// The segment (x0, y0)-(x1, y1) clipped to [0, width] x [0, height] (Liang-Barsky), or null.
function clip(x0, y0, x1, y1, width, height) {
  const dx = x1 - x0, dy = y1 - y0;
  let t0 = 0, t1 = 1;
  for (const [p, q] of [[-dx, x0], [dx, width - x0], [-dy, y0], [dy, height - y0]]) {
    if (p === 0) {
      if (q < 0) return null;
    } else {
      const t = q / p;
      if (p < 0) { if (t > t1) return null; if (t > t0) t0 = t; } else { if (t < t0) return null; if (t < t1) t1 = t; }
    }
  }
  return [x0 + t0 * dx, y0 + t0 * dy, x0 + t1 * dx, y0 + t1 * dy];
}
