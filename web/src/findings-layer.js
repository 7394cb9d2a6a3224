// SPDX-License-Identifier: MIT
// The map's inspection findings on the map (GET /api/maps/ID/findings): each at its place along its
// pipe, filled by its class for the robot (the risk table's: impassable, blockage, danger, none)
// and ringed by what the planner makes of it in the chosen risk mode (closed: a thick black ring;
// weighed with its probability: a blue ring, its width by the probability; ignored: no ring, pale).
// Hovering one names its DIN EN 13508-2 code, the code's name, the class and the reason.
import { ScatterplotLayer } from '@deck.gl/layers';
import { pointOnPipe } from './geometry.js';

export const kClassColours = {
  impassable: [150, 0, 60], blockage: [245, 130, 0], danger: [235, 205, 0], none: [150, 150, 150],
};
export const kUseRings = { closed: [0, 0, 0], weighed: [0, 90, 220], ignored: [0, 0, 0, 0] };
const kRadius = 5;  // pixels

// The findings document with each finding's point on the map (none for a pipe without a place).
export function placeFindings(map, doc) {
  const placed = [];
  for (const f of doc?.findings ?? []) {
    const pipe = map.pipeByName.get(f.pipe);
    if (!pipe || pipe.placeless) continue;
    placed.push({ ...f, at: pointOnPipe(pipe, f.offset_m) });
  }
  return placed;
}

export function findingsLayer(placed) {
  return new ScatterplotLayer({
    // An array of the layer's own: `placed` is the page's state (map-view.js draws only new arrays).
    id: 'findings', data: [...placed], getPosition: (f) => f.at, radiusUnits: 'pixels',
    getRadius: (f) => (f.planner === 'ignored' ? kRadius - 1 : kRadius),
    getFillColor: (f) => [...kClassColours[f.class] ?? kClassColours.none, f.planner === 'ignored' ? 120 : 255],
    stroked: true, lineWidthUnits: 'pixels',
    getLineColor: (f) => kUseRings[f.planner] ?? kUseRings.ignored,
    getLineWidth: (f) => (f.planner === 'closed' ? 3 : f.planner === 'weighed' ? 1 + 3 * f.probability : 0),
  });
}

// The finding drawn nearest to `coordinate` (map metres) within its circle and 3 pixels, at `zoom`
// (2^zoom pixels a metre), or null.
export function findingAt(placed, coordinate, zoom) {
  if (!coordinate) return null;
  const reach = (kRadius + 3) / 2 ** zoom;
  let best = null, bestD = reach * reach;
  for (const f of placed) {
    const dx = f.at[0] - coordinate[0], dy = f.at[1] - coordinate[1], d = dx * dx + dy * dy;
    if (d <= bestD) { best = f; bestD = d; }
  }
  return best;
}

// One line for the hover: "BBA roots (DIN EN 13508-2), characterisation B, 10 %: blockage, p 0.30
// — weighed by the planner; pipe S1 at 7.50 m".
export function describeFinding(f) {
  const what = `${f.code}${f.name ? ` ${f.name}` : ''} (DIN EN 13508-2)` +
    `${f.characterisation ? `, characterisation ${f.characterisation}` : ''}` +
    `${f.quantity1 !== undefined ? `, quantification ${f.quantity1}` : ''}`;
  const effect = f.class === 'blockage' ? `blockage, p ${f.probability.toFixed(2)}` : f.class;
  return `${what}: class ${effect}${f.reason && f.class !== 'none' ? ` (${f.reason})` : ''} — ${f.planner} by the planner; ` +
         `pipe ${f.pipe} at ${f.offset_m.toFixed(2)} m`;
}
