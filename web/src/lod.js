// SPDX-License-Identifier: MIT
// Level of detail for the map view: what a frame draws follows what is on the screen, not the
// network's size. Software WebGL (SwiftShader, on a machine without a GPU) pays about 40 µs for
// each instance of deck.gl's instanced layers (a line, a circle) in every frame, and a textured
// quad over the whole view costs more than a frame; a 2-D canvas draws an image in a few
// milliseconds. So the network is drawn as:
//  - 'vector': the window's pipes and manholes as deck.gl layers, when it holds at most
//    kVectorBudget of them (small maps, deep zoom);
//  - 'detail': else the window drawn once into an image (canvas 2D, in a worker: raster-worker.js)
//    at the level's resolution times the screen's device pixel ratio (imageSize), each pipe and
//    manhole; the view shows it in a 2-D canvas under deck.gl's, moved and scaled at each frame.
//    Another profile repaints the image from its layers (WindowImage), not the window's pipes
//    one by one. Up to kDetailBudget pipes in the window;
//  - 'overview': else the same image of the window merged: manholes closer than kMergePx on the
//    screen merge (their cell's mean position), pipes become one line per pair of merged cells and
//    vanish inside one cell; only exits are drawn as circles, small ones.
// The window is the view and a quarter of it on each side, in the grid's cells (GridIndex); it is
// rebuilt only when the view leaves it or the zoom rounds to another level, so a pan or a zoom
// within a level moves the same buffers or the same image. Picking runs on the grid too (nearest
// drawn feature under the pointer, on the CPU): a hover names the pipe under the pointer at any
// zoom without drawing the scene again, as deck.gl's GPU picking would.

export const kVectorBudget = 1200;   // pipes and manholes in a window drawn as deck.gl layers
export const kDetailBudget = 30000;  // pipes in a window drawn one by one into its image
export const kMergePx = 4;           // the overview's cell, in screen pixels at the level's zoom
const kMarginShare = 0.25;           // the window: the view and this share of its size each side
const kMaxImagePx = 4096;            // the image's largest side
const kMaxImagePixels = 12e6;        // its pixels (48 MB)
const kPickPx = 4;                   // how far from a line the pointer still picks it, in pixels
const kOverviewExitPx = 2.5;         // an exit's radius in the overview

// Pipe classes, their colours and the widths of each pipe drawn.
export const kNormal = 0, kOpenEnd = 1, kBlocked = 2;
export const kClassColor = [[60, 90, 160, 255], [140, 140, 140, 255], [200, 40, 40, 255]];
export const kExitColor = [20, 150, 60, 255], kManholeColor = [90, 90, 90, 255];
export const pipeWidthPx = (diameter) => 1 + 4 * Math.min(diameter, 1);
export const manholeRadiusPx = (exit, slots) => (exit ? 6 : 3 + Math.min(slots, 4) * 0.5);

// The map as columns (geometry.js reads them from the server's): each pipe's ends (x0, y0, x1, y1),
// diameter and open-end flag, each manhole's position (x, y), exit flag and slot count.
export const mapColumns = (map) => ({ ...map.columns, openEnd: map.openEnd });

// The same columns for the worker, with the buffers to transfer to it: a copy of each column alone
// (a column read in place from the server's geometry is a view of the whole buffer, which
// postMessage would copy whole, once for each column), made once a map.
export function workerColumns(map) {
  const columns = Object.fromEntries(Object.entries(mapColumns(map)).map(([name, a]) => [name, a.slice()]));
  return { columns, transfer: Object.values(columns).map((a) => a.buffer) };
}

// The pipes and manholes (mapColumns) in a uniform grid of about 8 a cell, in compressed rows:
// the pipes of cell c are pipeItems[pipeStart[c] .. pipeStart[c + 1]), each pipe in every cell its
// bounding box touches; each manhole in its one cell. O(pipes + manholes) to build (and the cells
// a long pipe crosses).
export class GridIndex {
  constructor(columns) {
    Object.assign(this, columns);
    const e = this.ends, p = this.positions;
    const pipes = this.diameters.length, manholes = this.exits.length;
    let x0 = Infinity, y0 = Infinity, x1 = -Infinity, y1 = -Infinity;
    for (let k = 0; k < e.length; k += 2) {
      if (Number.isNaN(e[k])) continue;  // a pipe with no position (geometry.js): in no cell
      x0 = Math.min(x0, e[k]); x1 = Math.max(x1, e[k]); y0 = Math.min(y0, e[k + 1]); y1 = Math.max(y1, e[k + 1]);
    }
    for (let k = 0; k < p.length; k += 2) {
      x0 = Math.min(x0, p[k]); x1 = Math.max(x1, p[k]); y0 = Math.min(y0, p[k + 1]); y1 = Math.max(y1, p[k + 1]);
    }
    if (!(x0 <= x1)) x0 = y0 = x1 = y1 = 0;  // an empty map
    const across = Math.max(1, Math.ceil(Math.sqrt(Math.max(pipes, manholes) / 8)));
    this.cell = Math.max(x1 - x0, y1 - y0, 1) / across;
    this.x0 = x0; this.y0 = y0;
    this.nx = Math.ceil((x1 - x0) / this.cell) + 1;
    this.ny = Math.ceil((y1 - y0) / this.cell) + 1;
    [this.pipeStart, this.pipeItems] = this.#rows(pipes, (i, visit) => {
      if (Number.isNaN(e[4 * i])) return;
      this.#cells(Math.min(e[4 * i], e[4 * i + 2]), Math.min(e[4 * i + 1], e[4 * i + 3]),
                  Math.max(e[4 * i], e[4 * i + 2]), Math.max(e[4 * i + 1], e[4 * i + 3]), visit);
    });
    [this.manholeStart, this.manholeItems] = this.#rows(manholes, (i, visit) => {
      visit(this.#cx(p[2 * i]) + this.#cy(p[2 * i + 1]) * this.nx);
    });
    this.seen = new Uint32Array(pipes);  // query stamps: a pipe in several cells is listed once
    this.stamp = 0;
  }

  #cx(x) { return Math.min(this.nx - 1, Math.max(0, Math.floor((x - this.x0) / this.cell))); }
  #cy(y) { return Math.min(this.ny - 1, Math.max(0, Math.floor((y - this.y0) / this.cell))); }

  // Calls visit(cell) for each cell of the rectangle (clamped to the grid).
  #cells(x0, y0, x1, y1, visit) {
    const cx1 = this.#cx(x1), cy1 = this.#cy(y1);
    for (let cy = this.#cy(y0); cy <= cy1; ++cy) {
      for (let cx = this.#cx(x0); cx <= cx1; ++cx) visit(cx + cy * this.nx);
    }
  }

  // Compressed rows of `count` items, each placed in its cells by place(i, visit(cell)).
  #rows(count, place) {
    const cells = this.nx * this.ny;
    const start = new Uint32Array(cells + 1);
    for (let i = 0; i < count; ++i) place(i, (c) => { ++start[c + 1]; });
    for (let c = 0; c < cells; ++c) start[c + 1] += start[c];
    const items = new Uint32Array(start[cells]);
    const fill = start.slice(0, -1);
    for (let i = 0; i < count; ++i) place(i, (c) => { items[fill[c]++] = i; });
    return [start, items];
  }

  // The rectangle [x0, y0, x1, y1] grown to whole cells (what a window covers).
  snap([x0, y0, x1, y1]) {
    const c = this.cell;
    return [this.x0 + Math.floor((x0 - this.x0) / c) * c, this.y0 + Math.floor((y0 - this.y0) / c) * c,
            this.x0 + Math.ceil((x1 - this.x0) / c) * c, this.y0 + Math.ceil((y1 - this.y0) / c) * c];
  }

  // How many pipes and manholes the rectangle's cells hold (a pipe in two cells counted twice):
  // O(cells).
  counts([x0, y0, x1, y1]) {
    let pipes = 0, manholes = 0;
    this.#cells(x0, y0, x1, y1, (c) => {
      pipes += this.pipeStart[c + 1] - this.pipeStart[c];
      manholes += this.manholeStart[c + 1] - this.manholeStart[c];
    });
    return { pipes, manholes };
  }

  // The pipes whose cells meet the rectangle, each once: O(cells + their pipes).
  pipesIn([x0, y0, x1, y1]) {
    const out = [];
    if (++this.stamp === 0xffffffff) { this.seen.fill(0); this.stamp = 1; }
    this.#cells(x0, y0, x1, y1, (c) => {
      for (let k = this.pipeStart[c]; k < this.pipeStart[c + 1]; ++k) {
        const i = this.pipeItems[k];
        if (this.seen[i] !== this.stamp) { this.seen[i] = this.stamp; out.push(i); }
      }
    });
    return out;
  }

  // The manholes in the rectangle's cells: O(cells + their manholes).
  manholesIn([x0, y0, x1, y1]) {
    const out = [];
    this.#cells(x0, y0, x1, y1, (c) => {
      for (let k = this.manholeStart[c]; k < this.manholeStart[c + 1]; ++k) out.push(this.manholeItems[k]);
    });
    return out;
  }

  // Squared distance from (x, y) to pipe i's segment.
  distance2(i, x, y) {
    const e = this.ends;
    const ax = e[4 * i], ay = e[4 * i + 1], dx = e[4 * i + 2] - ax, dy = e[4 * i + 3] - ay;
    const t = Math.max(0, Math.min(1, ((x - ax) * dx + (y - ay) * dy) / (dx * dx + dy * dy || 1)));
    return (ax + t * dx - x) ** 2 + (ay + t * dy - y) ** 2;
  }

  radius(m) { return manholeRadiusPx(this.exits[m], this.slots[m]); }
}

// Each pipe's class (kNormal, kOpenEnd, kBlocked) for a profile's blocked pipes (name -> reason).
// O(pipes + blocked): no pipe's name is read but the blocked ones'.
export function pipeClasses(map, blocked) {
  const classes = Uint8Array.from(map.openEnd, (open) => (open ? kOpenEnd : kNormal));
  if (blocked.size === 0) return classes;
  for (const name of blocked.keys()) {
    const i = map.pipeIndex(name);
    if (i !== undefined) classes[i] = kBlocked;
  }
  return classes;
}

// The view as the LOD sees it: {rect: [x0, y0, x1, y1] in metres, zoom (z: 2^z CSS pixels a
// metre), dpr (the screen's device pixels a CSS pixel; 1 if not given)}. Its key: the level (the zoom
// rounded), the window, how it is drawn and the pixel ratio its image is drawn for.
export function lodKey(index, view) {
  const level = Math.round(view.zoom);
  const [x0, y0, x1, y1] = view.rect;
  const mx = (x1 - x0) * kMarginShare, my = (y1 - y0) * kMarginShare;
  const window = index.snap([x0 - mx, y0 - my, x1 + mx, y1 + my]);
  const n = index.counts(window);
  const mode = n.pipes + n.manholes <= kVectorBudget ? 'vector' : n.pipes <= kDetailBudget ? 'detail' : 'overview';
  return { level, window, mode, dpr: view.dpr ?? 1 };
}

// Whether `key` still serves the view: the same level and pixel ratio, the view inside its window.
export function keyServes(key, view) {
  if (!key || key.level !== Math.round(view.zoom) || key.dpr !== (view.dpr ?? 1)) return false;
  const [x0, y0, x1, y1] = view.rect, w = key.window;
  return x0 >= w[0] && y0 >= w[1] && x1 <= w[2] && y1 <= w[3];
}

// What the view draws for a 'vector' key: {pipes, manholes} as deck.gl's binary data
// ({length, attributes}) for a LineLayer and a ScatterplotLayer. Positions are Float64Array:
// deck.gl keeps their double precision, which a map in national grid metres needs.
export function vectorData(index, key, classes) {
  const e = index.ends;
  const ids = index.pipesIn(key.window);
  const n = ids.length;
  const src = new Float64Array(3 * n), dst = new Float64Array(3 * n), color = new Uint8Array(4 * n);
  const width = new Float32Array(n);
  ids.forEach((i, k) => {
    src.set([e[4 * i], e[4 * i + 1], 0], 3 * k);
    dst.set([e[4 * i + 2], e[4 * i + 3], 0], 3 * k);
    color.set(kClassColor[classes[i]], 4 * k);
    width[k] = pipeWidthPx(index.diameters[i]);
  });
  const pipes = { length: n, attributes: { getSourcePosition: { value: src, size: 3 },
                                           getTargetPosition: { value: dst, size: 3 },
                                           getColor: { value: color, size: 4 }, getWidth: { value: width, size: 1 } } };
  const mids = index.manholesIn(key.window);
  const position = new Float64Array(3 * mids.length), radius = new Float32Array(mids.length);
  const fill = new Uint8Array(4 * mids.length);
  mids.forEach((m, k) => {
    position.set([index.positions[2 * m], index.positions[2 * m + 1], 0], 3 * k);
    radius[k] = index.radius(m);
    fill.set(index.exits[m] ? kExitColor : kManholeColor, 4 * k);
  });
  const manholes = { length: mids.length, attributes: { getPosition: { value: position, size: 3 },
                                                        getRadius: { value: radius, size: 1 },
                                                        getFillColor: { value: fill, size: 4 } } };
  return { pipes, manholes };
}

// The image of a window at a level: its size in pixels and its resolution (pixels a metre): the
// level's zoom times the screen's device pixel ratio (so that the image is as sharp as the screen
// at that zoom), within kMaxImagePx a side and kMaxImagePixels in all (the worker holds three
// images of this size and the page one: at most 4 x 48 MB). scale: image pixels a CSS pixel at the
// level's zoom (the device pixel ratio, or less where the caps bind): widths and radii, given in
// CSS pixels, are drawn times this.
export function imageSize([x0, y0, x1, y1], level, dpr = 1) {
  const w = x1 - x0, h = y1 - y0;
  const res = Math.min(2 ** level * dpr, kMaxImagePx / Math.max(w, h, 1e-9),
                       Math.sqrt(kMaxImagePixels / Math.max(w * h, 1e-18)));
  return { res, scale: res / 2 ** level,
           width: Math.max(1, Math.round(w * res)), height: Math.max(1, Math.round(h * res)) };
}

// The image of a 'detail' or 'overview' key's window (the worker's job), in layers, so that
// another profile's classes repaint only what they change: the pipes in their classes without
// a profile (normal or open end) and the manholes are drawn once for the window, each into a
// bitmap; the image is the pipes' bitmap, the blocked pipes over it in red, then the manholes'
// bitmap (blocked pipes on top of the others, manholes on top of all). compose(classes) makes the
// image: two blits and the blocked pipes' strokes, from coordinates projected once.
export class WindowImage {
  constructor(index, key) {
    this.key = key;
    const [x0, , , y1] = key.window;
    const { res, scale, width, height } = imageSize(key.window, key.level, key.dpr);
    Object.assign(this, { width, height, bounds: key.window });
    const px = (x) => (x - x0) * res, py = (y) => (y1 - y) * res;  // y up on the map, down in the image
    const e = index.ends;
    // The lines drawn: their ends in pixels and widths, and what makes one blocked. In detail each
    // pipe of the window (line k is pipe pipes[k]); in the overview the merged lines, line
    // lineOf[k] standing for pipes[k] (-1: none, the pipe is inside one cell).
    let pipes, lineOf, ends, base, widths, blockedWidth = null, manholes, radius;
    if (key.mode === 'detail') {
      pipes = Uint32Array.from(index.pipesIn(key.window));
      ends = new Float32Array(4 * pipes.length);
      base = new Uint8Array(pipes.length);
      widths = new Float32Array(pipes.length);
      pipes.forEach((i, k) => {
        ends.set([px(e[4 * i]), py(e[4 * i + 1]), px(e[4 * i + 2]), py(e[4 * i + 3])], 4 * k);
        base[k] = index.openEnd[i] ? kOpenEnd : kNormal;
        widths[k] = Math.max(0.5, Math.round(2 * pipeWidthPx(index.diameters[i]) * scale) / 2);
      });
      manholes = index.manholesIn(key.window);
      radius = (m) => index.radius(m) * scale;
    } else {
      const merged = mergedLines(index, key);
      ({ pipes, lineOf } = merged);
      ends = merged.ends.map((v, k) => (k % 2 === 0 ? px(v) : py(v)));
      base = merged.base;
      widths = new Float32Array(base.length).fill(scale);
      blockedWidth = 2 * scale;
      manholes = index.manholesIn(key.window).filter((m) => index.exits[m]);
      radius = () => kOverviewExitPx * scale;
    }
    Object.assign(this, { pipes, lineOf, ends, widths, blockedWidth });
    this.canvas = new OffscreenCanvas(width, height);
    const g = this.canvas.getContext('2d');
    g.lineCap = 'round';
    for (const cls of [kNormal, kOpenEnd]) this.#stroke(g, kClassColor[cls], (k) => base[k] === cls);
    this.pipesLayer = this.canvas.transferToImageBitmap();
    const fills = new Map();
    for (const m of manholes) {
      const exit = index.exits[m], r = radius(m);
      const k = exit * 1000 + r;
      let f = fills.get(k);
      if (!f) fills.set(k, (f = { color: exit ? kExitColor : kManholeColor, path: new Path2D() }));
      const x = px(index.positions[2 * m]), y = py(index.positions[2 * m + 1]);
      f.path.moveTo(x + r, y);
      f.path.arc(x, y, r, 0, 2 * Math.PI);
    }
    for (const f of fills.values()) {
      g.fillStyle = rgb(f.color);
      g.fill(f.path);
    }
    this.manholesLayer = this.canvas.transferToImageBitmap();
  }

  // Whether this image is the one `key` asks for (the same window, level, mode and pixel ratio).
  serves(key) {
    const k = this.key;
    return key.level === k.level && key.mode === k.mode && key.dpr === k.dpr && key.window.every((v, i) => v === k.window[i]);
  }

  // The image for the pipes' classes (each pipe's: kNormal, kOpenEnd, kBlocked), an ImageBitmap.
  compose(classes) {
    const g = this.canvas.getContext('2d');
    g.drawImage(this.pipesLayer, 0, 0);
    let blocked;
    if (this.lineOf) {  // a merged line is blocked if any of its pipes is
      blocked = new Uint8Array(this.widths.length);
      this.pipes.forEach((i, k) => { if (classes[i] === kBlocked && this.lineOf[k] >= 0) blocked[this.lineOf[k]] = 1; });
    } else {
      blocked = Uint8Array.from(this.pipes, (i) => (classes[i] === kBlocked ? 1 : 0));
    }
    g.lineCap = 'round';
    this.#stroke(g, kClassColor[kBlocked], (k) => blocked[k] === 1, this.blockedWidth);
    g.drawImage(this.manholesLayer, 0, 0);
    return this.canvas.transferToImageBitmap();
  }

  close() {
    this.pipesLayer.close();
    this.manholesLayer.close();
  }

  // Strokes the lines k with drawn(k) in `color`: one path per width, a few strokes whatever the
  // count; at `width` if given, else each line's own.
  #stroke(g, color, drawn, width = null) {
    const paths = new Map();
    const a = this.ends;
    for (let k = 0; k < this.widths.length; ++k) {
      if (!drawn(k)) continue;
      const w = width ?? this.widths[k];
      let path = paths.get(w);
      if (!path) paths.set(w, (path = new Path2D()));
      path.moveTo(a[4 * k], a[4 * k + 1]);
      path.lineTo(a[4 * k + 2], a[4 * k + 3]);
    }
    g.strokeStyle = rgb(color);
    for (const [w, path] of paths) {
      g.lineWidth = w;
      g.stroke(path);
    }
  }
}

const rgb = (c) => `rgb(${c[0]},${c[1]},${c[2]})`;

// Pipes merged by cells of kMergePx pixels at the level's zoom: one line per pair of cells that a
// pipe joins, between the cells' mean end positions, in its first pipe's class without a profile
// (normal or open end; WindowImage draws it blocked if any of its pipes is, so a profile's limits
// stay visible): {ends: [x0, y0, x1, y1, ...], base, pipes (the window's), lineOf (each of those
// pipes' line, -1 inside one cell)}. O(pipes in the window).
function mergedLines(index, key) {
  const e = index.ends;
  const [wx0, wy0, wx1, wy1] = key.window;
  const size = kMergePx * 2 ** -key.level;
  const nx = Math.max(1, Math.ceil((wx1 - wx0) / size)), ny = Math.max(1, Math.ceil((wy1 - wy0) / size));
  const cellOf = (x, y) => Math.min(nx - 1, Math.max(0, Math.floor((x - wx0) / size))) +
                           nx * Math.min(ny - 1, Math.max(0, Math.floor((y - wy0) / size)));
  const sums = new Map();   // cell -> [sum x, sum y, count]
  const edges = new Map();  // a * cells + b (a < b) -> [a, b, class, line]
  const cells = nx * ny;
  const add = (cell, x, y) => {
    const s = sums.get(cell);
    if (s) { s[0] += x; s[1] += y; ++s[2]; } else sums.set(cell, [x, y, 1]);
  };
  const pipes = Uint32Array.from(index.pipesIn(key.window)), lineOf = new Int32Array(pipes.length).fill(-1);
  pipes.forEach((i, k) => {
    const ax = e[4 * i], ay = e[4 * i + 1], bx = e[4 * i + 2], by = e[4 * i + 3];
    const a = cellOf(ax, ay), b = cellOf(bx, by);
    add(a, ax, ay);
    add(b, bx, by);
    if (a === b) return;  // within a cell: not drawn
    const key = Math.min(a, b) * cells + Math.max(a, b);
    let edge = edges.get(key);
    if (!edge) edges.set(key, (edge = [a, b, index.openEnd[i] ? kOpenEnd : kNormal, edges.size]));
    lineOf[k] = edge[3];
  });
  const ends = new Float64Array(4 * edges.size), base = new Uint8Array(edges.size);
  for (const [a, b, c, line] of edges.values()) {
    const sa = sums.get(a), sb = sums.get(b);
    ends.set([sa[0] / sa[2], sa[1] / sa[2], sb[0] / sb[2], sb[1] / sb[2]], 4 * line);
    base[line] = c;
  }
  return { ends, base, pipes, lineOf };
}

// The drawn feature at `at` (a point in metres) when the view's zoom is `zoom`: a manhole drawn
// there (within its circle and a pixel; in the overview only exits are drawn, smaller), else the nearest
// pipe within its half width and kPickPx pixels (in the overview, the merged lines stand for the
// window's pipes, so the nearest pipe of all is named). {kind: 'manhole' | 'pipe', index} or
// null. O(cells near the point and their features).
export function pick(index, overview, at, zoom) {
  const mpp = 2 ** -zoom;  // metres a pixel
  const [x, y] = at;
  const near = [x - 8 * mpp, y - 8 * mpp, x + 8 * mpp, y + 8 * mpp];
  let best = null, bestD = Infinity;
  for (const m of index.manholesIn(near)) {
    if (overview && !index.exits[m]) continue;
    const d = Math.hypot(index.positions[2 * m] - x, index.positions[2 * m + 1] - y) / mpp;
    if (d <= (overview ? kOverviewExitPx : index.radius(m)) + 1 && d < bestD) { best = { kind: 'manhole', index: m }; bestD = d; }
  }
  if (best) return best;
  for (const i of index.pipesIn(near)) {
    const d = Math.sqrt(index.distance2(i, x, y)) / mpp;
    const reach = (overview ? 0 : pipeWidthPx(index.diameters[i]) / 2) + kPickPx;
    if (d <= reach && d < bestD) { best = { kind: 'pipe', index: i }; bestD = d; }
  }
  return best;
}
