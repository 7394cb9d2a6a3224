// SPDX-License-Identifier: MIT
// The warnings of the map's reader and of its condition data (the server's `warnings`: {where,
// message}), listed under the map, each linked to what it is about on the map: a click on it
// highlights those pipes and manholes and brings them into view. A message names its objects
// ("manhole 119016PU01 has no pipes", "finding BCE in pipe 119015: ..."); the network "in N
// disconnected parts" names none, so the page finds the parts itself (from the pipes' ends) and
// links every part but the largest. A warning that counts objects without naming them ("25
// manholes have no shaft size") has nothing to link and is listed as it is.
//
//   const objects = warningObjects(map, warning);   // {pipes: [name], manholes: [name]} or null
//   renderWarnings(list, map, warnings, (objects) => { ... highlight, focus ... });

// "pipe NAME" / "manhole NAME" (a name as written, or in single quotes) that the map has.
export function warningObjects(map, warning) {
  const text = warning.message;
  if (/disconnected parts/.test(text)) return smallParts(map);
  const found = { pipes: [], manholes: [] };
  for (const [, kind, quoted, bare] of text.matchAll(/\b(pipe|manhole) (?:'([^']*)'|([^\s:,;()']+))/g)) {
    const name = quoted ?? bare;
    const has = kind === 'pipe' ? map.pipeByName.has(name) : map.manholeByName.has(name);
    const into = kind === 'pipe' ? found.pipes : found.manholes;
    if (has && !into.includes(name)) into.push(name);
  }
  return found.pipes.length + found.manholes.length > 0 ? found : null;
}

// The manholes and pipes of every connected part of the network but the largest (union-find over
// the pipes' ends): what "the network falls into N disconnected parts" is about.
export function smallParts(map) {
  const { from, to } = map.ends;
  const parent = Uint32Array.from({ length: map.manholeCount }, (_, i) => i);
  const root = (i) => { while (parent[i] !== i) i = parent[i] = parent[parent[i]]; return i; };
  for (let j = 0; j < map.pipeCount; ++j) {
    if (from[j] < map.manholeCount && to[j] < map.manholeCount) parent[root(from[j])] = root(to[j]);
  }
  const size = new Map();
  for (let i = 0; i < map.manholeCount; ++i) size.set(root(i), (size.get(root(i)) ?? 0) + 1);
  if (size.size < 2) return null;
  const largest = [...size].reduce((a, b) => (b[1] > a[1] ? b : a))[0];
  const manholes = [], pipes = [];
  for (let i = 0; i < map.manholeCount; ++i) if (root(i) !== largest) manholes.push(map.manhole(i).name);
  for (let j = 0; j < map.pipeCount; ++j) {
    const end = from[j] < map.manholeCount ? from[j] : to[j];
    if (end < map.manholeCount && root(end) !== largest) pipes.push(map.pipe(j).name);
  }
  return { pipes, manholes };
}

// The list: "where: message" (the where shortened to its file's name and record), a link where
// the warning has objects on the map; onShow(objects) when one is clicked.
export function renderWarnings(list, map, warnings, onShow) {
  list.replaceChildren(...warnings.map((w) => {
    const li = document.createElement('li');
    const objects = warningObjects(map, w);
    // The file by its name, and the record (a line, or the end of an XML path): the whole in the tooltip.
    const [file, ...rest] = w.where.split(':');
    const record = rest.join(':');
    const where = `${file.replace(/^.*\//, '')}${record ? `:${record.length > 40 ? `…${record.slice(-40)}` : record}` : ''}`;
    li.title = `${w.where}: ${w.message}`;
    if (!objects) {
      li.textContent = `${where}: ${w.message}`;
      return li;
    }
    const a = Object.assign(document.createElement('a'), { href: '#', textContent: w.message });
    a.onclick = (e) => { e.preventDefault(); onShow(objects); };
    li.append(`${where}: `, a);
    return li;
  }));
}
