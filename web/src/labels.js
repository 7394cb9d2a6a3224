// SPDX-License-Identifier: MIT
// Manhole names thinned so that no two overlap: at a zoom each name is a box of its text's width
// and height in screen pixels around its manhole; the names are taken in order of priority (exits
// first, then the map's order) and one is kept only if its box meets no box kept before it. The
// boxes are found through a grid of cells in screen pixels, so thinning n names is O(n).
//
// Thinned at zoom z, the names kept never overlap at any zoom above z either: the boxes keep their
// size in pixels while the distances between manholes grow. map-view.js thins at the zoom rounded
// down to a quarter level, and again only when the view's zoom leaves that quarter.
//
//   thinLabels(map.manholes, zoom, (name) => name.length * 7)   // the manholes whose names show

export const kLabelHeightPx = 13;  // an 11 px font's line
const kGapPx = 2;                  // space kept between two names
const kCellPx = 64;

// `manholes`: [{name, position: [x, y], exit}]; `width(name)`: the text's width in CSS pixels.
// Returns the manholes whose names are drawn, in priority order.
export function thinLabels(manholes, zoom, width) {
  const s = 2 ** zoom;
  const order = [...manholes].sort((a, b) => Number(b.exit) - Number(a.exit));
  const cells = new Map();
  const kept = [];
  for (const m of order) {
    const w = width(m.name) + kGapPx, h = kLabelHeightPx + kGapPx;
    const cx = m.position[0] * s, cy = m.position[1] * s;
    const box = [cx - w / 2, cy - h / 2, cx + w / 2, cy + h / 2];
    const i0 = Math.floor(box[0] / kCellPx), i1 = Math.floor(box[2] / kCellPx);
    const j0 = Math.floor(box[1] / kCellPx), j1 = Math.floor(box[3] / kCellPx);
    let free = true;
    for (let i = i0; i <= i1 && free; ++i) {
      for (let j = j0; j <= j1 && free; ++j) {
        for (const b of cells.get(`${i},${j}`) ?? []) {
          if (b[0] < box[2] && box[0] < b[2] && b[1] < box[3] && box[1] < b[3]) { free = false; break; }
        }
      }
    }
    if (!free) continue;
    kept.push(m);
    for (let i = i0; i <= i1; ++i) {
      for (let j = j0; j <= j1; ++j) {
        const k = `${i},${j}`;
        if (!cells.has(k)) cells.set(k, []);
        cells.get(k).push(box);
      }
    }
  }
  return kept;
}

// The width of a name as the names' TextLayer draws it (11 px monospace), measured once per name.
export function labelWidth() {
  const g = document.createElement('canvas').getContext('2d');
  g.font = '11px monospace';
  const widths = new Map();
  return (name) => {
    let w = widths.get(name);
    if (w === undefined) widths.set(name, (w = Math.ceil(g.measureText(name).width)));
    return w;
  };
}
