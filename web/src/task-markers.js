// SPDX-License-Identifier: MIT
// The mission's marks on the map: the start and each task, told apart by kind (sample, inspection,
// go-to, end: each its own colour, as the legend says) and numbered in the order the plan does
// them (its steps name their tasks: plan --json's "task"); before a plan, each shows its kind's
// letter. A dropped task is grey, a done one ringed green.
import { ScatterplotLayer, TextLayer } from '@deck.gl/layers';
import { placePoint } from './geometry.js';

export const kTaskKinds = ['start', 'sample', 'inspection', 'go-to', 'end'];
export const kTaskColours = {
  start: [255, 255, 255], sample: [30, 140, 230], inspection: [150, 60, 200], 'go-to': [0, 165, 140], end: [40, 40, 40],
};
const kLetters = { start: 'S', sample: 's', inspection: 'i', 'go-to': 'g', end: 'E' };

export function taskKind(t) {
  if (t.type === 'start') return 'start';
  if (t.final) return 'end';
  return t.type === 'take_water_sample' ? 'sample' : t.type === 'inspect_pipe' ? 'inspection' : 'go-to';
}

// Each task's number in the plan's order (1, 2, ...): the first step that names it. The end, which
// the last step reaches without a step of its own when it is in a pipe, is numbered last
// (taskMarks).
export function planOrder(steps) {
  const order = new Map();
  for (const s of steps ?? []) {
    if (s.task && !order.has(s.task)) order.set(s.task, order.size + 1);
  }
  return order;
}

// s: {mission, dropped: Set, done: Set, planOrder: Map(task -> number)}
export function taskMarks(map, s) {
  const marks = s.mission.tasks.map((t) => ({ t, kind: taskKind(t), at: placePoint(map, t.at ?? { pipe: t.pipe }) }))
    .filter((x) => x.at);
  const start = placePoint(map, s.mission.start);
  if (start) marks.push({ t: { type: 'start', name: 'start' }, kind: 'start', at: start });
  for (const m of marks) {
    let n = s.planOrder?.get(m.t.name);
    if (n === undefined && m.kind === 'end' && s.planOrder?.size) n = s.planOrder.size + 1;
    m.label = n !== undefined ? String(n) : kLetters[m.kind];
  }
  return marks;
}

export function taskLayers(map, s) {
  const marks = taskMarks(map, s);
  const dark = (m) => m.kind !== 'start' && !s.dropped.has(m.t.name);
  return [
    new ScatterplotLayer({
      id: 'tasks', data: marks, getPosition: (m) => m.at, radiusUnits: 'pixels', getRadius: 9, stroked: true,
      getFillColor: (m) => (s.dropped.has(m.t.name) ? [170, 170, 170] : kTaskColours[m.kind]),
      getLineColor: (m) => (s.done.has(m.t.name) ? [60, 190, 90] : [0, 0, 0]), lineWidthUnits: 'pixels',
      getLineWidth: (m) => (s.done.has(m.t.name) ? 4 : 1),
      updateTriggers: { getFillColor: [s.dropped.size], getLineColor: [s.done.size], getLineWidth: [s.done.size] },
    }),
    new TextLayer({
      id: 'task-labels', data: marks, getPosition: (m) => m.at, getText: (m) => m.label, getSize: 11,
      getColor: (m) => (dark(m) ? [255, 255, 255] : [0, 0, 0]), fontWeight: 'bold', fontFamily: 'sans-serif',
      characterSet: 'auto', updateTriggers: { getColor: [s.dropped.size], getText: [s.planOrder] },
    }),
  ];
}
