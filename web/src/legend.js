// SPDX-License-Identifier: MIT
// The legend of what is drawn over the network besides the routes: the findings' classes and what
// the planner makes of them (findings-layer.js), the task markers by kind (task-markers.js) and
// what the robot learnt (learnt-layer.js). Shown only for what the map holds.
import { kClassColours, kUseRings } from './findings-layer.js';
import { kLearntColours } from './learnt-layer.js';
import { kTaskColours, kTaskKinds } from './task-markers.js';

const rgb = (c) => `rgba(${c[0]}, ${c[1]}, ${c[2]}, ${(c[3] ?? 255) / 255})`;
const dot = (fill, ring, width = 2) =>
  `<span class="dot" style="background:${rgb(fill)};border:${width}px solid ${rgb(ring)}"></span>`;

export function renderLegend(element, { findings, risk, learnt }) {
  const parts = [];
  parts.push(`<div>tasks: ${kTaskKinds.map((k) => `${dot(kTaskColours[k], [0, 0, 0], 1)}${k}`).join(' ')}` +
             ' (numbered in plan order)</div>');
  if (findings?.length) {
    const counts = (u) => findings.filter((f) => f.planner === u).length;
    parts.push(`<div data-legend="findings">findings by class: ${Object.entries(kClassColours)
      .map(([c, colour]) => `${dot(colour, [0, 0, 0, 0], 0)}${c}`).join(' ')}</div>`);
    parts.push(`<div>planner (${risk}): ${dot([255, 255, 255], kUseRings.closed, 3)}closed (${counts('closed')}) ` +
               `${dot([255, 255, 255], kUseRings.weighed, 2)}weighed by probability (${counts('weighed')}) ` +
               `${dot([150, 150, 150, 120], [0, 0, 0, 0], 0)}ignored (${counts('ignored')})</div>`);
  }
  if (learnt) {
    parts.push(`<div data-legend="learnt">learnt: ${dot(kLearntColours.blockage, [255, 255, 255])}blocked ` +
               `${dot(kLearntColours.danger, [255, 255, 255])}danger spot ` +
               `${dot([255, 255, 255, 0], kLearntColours.passage, 3)}passage closed ` +
               `${dot(kLearntColours.correction, [255, 255, 255])}map correction</div>`);
  }
  element.innerHTML = parts.join('');
}
