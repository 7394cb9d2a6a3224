// SPDX-License-Identifier: MIT
// The map as the page draws it: the server's geometry document (columns, the map's own metres)
// turned into one object per pipe and manhole, and points along a pipe.

// Columns -> {manholes, pipes, pipeByName, manholeByName}. A pipe with an open end (no manhole at
// one side) is drawn as a short stub from its one manhole, a tenth of its length long.
export function loadGeometry(g) {
  const m = g.manholes;
  const manholes = m.name.map((name, i) => ({ i, name, position: [m.x[i], m.y[i]], slots: m.slots[i],
                                              exit: m.exit[i] === 1 }));
  const p = g.pipes;
  const pipes = [];
  p.name.forEach((name, i) => {
    const a = p.from[i], b = p.to[i];
    if (a < 0 && b < 0) return;
    const known = manholes[a >= 0 ? a : b].position;
    const stub = [known[0] + Math.max(p.length_m[i] / 10, 0.5), known[1]];
    pipes.push({ i, name, from: a >= 0 ? known : stub, to: b >= 0 ? manholes[b].position : stub,
                 openEnd: a < 0 || b < 0, length_m: p.length_m[i], diameter_m: p.diameter_m[i] });
  });
  return { id: g.id, name: g.name, bounds: g.bounds, manholes, pipes,
           pipeByName: new Map(pipes.map((x) => [x.name, x])),
           manholeByName: new Map(manholes.map((x) => [x.name, x])) };
}

// The point `offset` metres from the pipe's `from` end (its middle without an offset).
export function pointOnPipe(pipe, offset) {
  const t = offset === undefined ? 0.5 : Math.max(0, Math.min(1, offset / pipe.length_m));
  return [pipe.from[0] + t * (pipe.to[0] - pipe.from[0]), pipe.from[1] + t * (pipe.to[1] - pipe.from[1])];
}

// The clicked offset along the pipe, from its `from` end, in metres of the pipe's length.
export function offsetOf(pipe, [x, y]) {
  const dx = pipe.to[0] - pipe.from[0], dy = pipe.to[1] - pipe.from[1];
  const t = ((x - pipe.from[0]) * dx + (y - pipe.from[1]) * dy) / (dx * dx + dy * dy || 1);
  return Math.round(Math.max(0, Math.min(1, t)) * pipe.length_m * 100) / 100;
}

// The place of a mission (docs/formats/mission-json.md) as a point on the map, or null.
export function placePoint(map, place) {
  if (!place) return null;
  if (place.pipe && map.pipeByName.has(place.pipe)) return pointOnPipe(map.pipeByName.get(place.pipe), place.offset_m);
  if (place.manhole && map.manholeByName.has(place.manhole)) return map.manholeByName.get(place.manhole).position;
  return null;
}

// The pipes a list of plan steps in the paper's text drives or enters, in order
// ("DRIVE_PIPE_TO_MANHOLE P1 M3"; "DRIVE_MANHOLE_TYPE_3_FROM_1_TO_2 M9 P8 P9 P14" enters its
// `to` slot's pipe, P9), as the server's route event lists them.
export function pipesOfSteps(map, steps) {
  const pipes = [];
  for (const s of steps) {
    const words = s.split(/\s+/);
    const passage = /FROM_\d+_TO_(\d+)$/.exec(words[0]);
    const pipe = passage ? words[1 + Number(passage[1])] : words.slice(1).find((w) => map.pipeByName.has(w));
    if (pipe && map.pipeByName.has(pipe) && pipes.at(-1) !== pipe) pipes.push(pipe);
  }
  return pipes;
}
