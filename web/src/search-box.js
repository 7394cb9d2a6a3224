// SPDX-License-Identifier: MIT
// Finding a manhole or a pipe by name, and the view that shows it. A name is looked up as typed
// (manholes first, then pipes), then ignoring case, then as the beginning of one name only; when
// several names begin so, the answer lists the first of them. The suggestions under the box are
// the first names that begin with what is typed.
//
//   const found = findPlace(map, 'SW12');   // {kind: 'manhole', name, points: [[x, y]]} or {error}
//   view.setView(viewOf(found, 1000, 700));

const kSuggestions = 20;

// Every name of the map, manholes then pipes, with its kind and index (read from the geometry's
// name table each time: no list is kept for a 100,000-manhole map).
function* names(map) {
  for (let i = 0; i < map.manholeCount; ++i) yield ['manhole', i, map.manhole(i).name];
  for (let i = 0; i < map.pipeCount; ++i) yield ['pipe', i, map.pipe(i).name];
}

function place(map, kind, i) {
  if (kind === 'manhole') {
    const m = map.manhole(i);
    return { kind, name: m.name, points: [m.position] };
  }
  const p = map.pipe(i);
  if (p.placeless) return { error: `pipe ${p.name} has no manhole at either end: it has no place on the map` };
  return { kind, name: p.name, points: [p.from, p.to] };
}

export function findPlace(map, text) {
  const name = text.trim();
  if (!name) return { error: 'type a manhole\'s or a pipe\'s name' };
  if (map.manholeByName.has(name)) return place(map, 'manhole', map.manholeByName.get(name).i);
  if (map.pipeByName.has(name)) return place(map, 'pipe', map.pipeIndex(name));
  const lower = name.toLowerCase();
  const starting = [];
  for (const [kind, i, n] of names(map)) {
    const l = n.toLowerCase();
    if (l === lower) return place(map, kind, i);
    if (l.startsWith(lower)) starting.push([kind, i, n]);
  }
  if (starting.length === 1) return place(map, starting[0][0], starting[0][1]);
  if (starting.length === 0) return { error: `no manhole or pipe named ${name}` };
  const shown = starting.slice(0, 5).map((s) => s[2]);
  return { error: `${starting.length} names begin with ${name}: ${shown.join(', ')}${starting.length > 5 ? ', ...' : ''}` };
}

// The first names that begin with `text` (any case), for the box's suggestions.
export function suggestions(map, text) {
  const lower = text.trim().toLowerCase();
  const out = [];
  if (!lower) return out;
  for (const [, , n] of names(map)) {
    if (n.toLowerCase().startsWith(lower)) out.push(n);
    if (out.length === kSuggestions) break;
  }
  return out;
}

// The view ({target, zoom}) centred on a found place: a pipe over a third of the view's smaller
// side, a manhole with 40 m around it; never closer than 16 pixels a metre.
export function viewOf(found, width, height) {
  const xs = found.points.map((p) => p[0]), ys = found.points.map((p) => p[1]);
  const target = [(Math.min(...xs) + Math.max(...xs)) / 2, (Math.min(...ys) + Math.max(...ys)) / 2];
  const size = Math.max(Math.max(...xs) - Math.min(...xs), Math.max(...ys) - Math.min(...ys));
  const span = found.kind === 'pipe' ? Math.max(3 * size, 10) : 40;
  return { target, zoom: Math.min(Math.log2(Math.min(width, height) / span), 4) };
}
