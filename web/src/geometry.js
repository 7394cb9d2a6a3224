// SPDX-License-Identifier: MIT
// The map as the page draws it (the server's geometry, in the map's own metres) and points along a
// pipe.

// The map as the page holds it, from the server's compact geometry (readGeometry, GET
// /api/maps/ID/geometry) or its JSON document of columns (loadGeometry): columns of typed arrays,
// read in place, and objects only for the pipes and manholes the page names or clicks:
//   {id, bounds, manholeCount, pipeCount, columns (lod.js's grid reads them: each pipe's ends and
//    diameter, each manhole's position, exit flag and slot count), openEnd [pipe],
//    placeless [pipe index], pipe(i), manhole(i), pipes, manholes, pipeIndex(name), pipeByName,
//    manholeByName}
// pipe(i) is {i, name, from, to, openEnd, placeless, length_m, diameter_m}, manhole(i) {i, name, position,
// slots, exit}; the arrays are built at their first use (a 100,000-manhole map is drawn without
// them). pipeIndex(name) is a pipe's index (undefined if none); pipeByName and manholeByName
// answer has(name) and get(name) (the object, a new one each time): the names are decoded and
// indexed by name at the first look-up, without building any object. A pipe with an open end (no
// manhole at one side) is drawn as a short stub from its one manhole, a tenth of its length long
// (at least 0.5 m). One with no manhole at either end (a JSON map's `"from": null, "to": null` or
// an ASCII map's `-`/`-`: the builder accepts it) has no position: the map has no geometry of its
// own for a pipe, only its manholes'. It is not drawn: its ends are NaN in the columns (lod.js's
// grid leaves it out), its object says placeless: true, and `placeless` lists the indices of all
// such pipes, for the page to name them; a task or fault placed in one has no point on the map.

const kNone = 0xffffffff;                 // a pipe end without a manhole (map_geometry.h)
export const kGeometryFormatVersion = 2;  // the compact geometry's format this page reads

// The server's compact geometry (server/src/map_geometry.h: a 56-byte header, then little-endian
// sections) as typed arrays over the buffer, no copy (on a little-endian machine, as every
// browser's is); a wrong magic, version or size throws.
export function readGeometry(buffer, id) {
  if (new Uint8Array(new Uint16Array([1]).buffer)[0] !== 1) throw new Error('the page reads the map geometry on little-endian machines only');
  const head = new DataView(buffer);
  const fail = (why) => { throw new Error(`map '${id}' geometry: ${why}`); };
  if (buffer.byteLength < 56) fail(`${buffer.byteLength} bytes, no header`);
  if (String.fromCharCode(...new Uint8Array(buffer, 0, 4)) !== 'SPGM') fail('not sewerplan geometry');
  const version = head.getUint32(4, true);
  if (version !== kGeometryFormatVersion) {
    fail(`format ${version}, this page reads format ${kGeometryFormatVersion}: the page and the server are of ` +
         'different versions (reload the page; if it stays, install them together)');
  }
  const m = head.getUint32(8, true), p = head.getUint32(12, true);
  const bounds = [0, 1, 2, 3].map((k) => head.getFloat64(16 + 8 * k, true));
  const nameBytes = head.getUint32(48, true);
  let at = 56;
  const take = (Type, n) => {
    const a = new Type(buffer, at, n);
    at += n * Type.BYTES_PER_ELEMENT;
    return a;
  };
  if (56 + 16 * m + 24 * p + 4 * (m + p + 1) + 3 * m + nameBytes !== buffer.byteLength) {
    fail(`${buffer.byteLength} bytes for ${m} manholes and ${p} pipes`);
  }
  const positions = take(Float64Array, 2 * m), lengths = take(Float64Array, p), diameters = take(Float64Array, p);
  const from = take(Uint32Array, p), to = take(Uint32Array, p), offsets = take(Uint32Array, m + p + 1);
  const slots = take(Uint16Array, m), exits = take(Uint8Array, m), names = take(Uint8Array, nameBytes);
  // What the arrays say, checked once: a wrong pipe end or name offset would draw nonsense quietly.
  for (let j = 0; j < p; ++j) {
    for (const [end, v] of [['from', from[j]], ['to', to[j]]]) {
      if (v !== kNone && v >= m) fail(`pipe ${j}'s ${end} is manhole ${v}, the map has ${m} manholes`);
    }
  }
  if (offsets[0] !== 0 || offsets[m + p] !== nameBytes) fail(`the name offsets do not span the ${nameBytes} bytes of names`);
  for (let k = 0; k < m + p; ++k) {
    if (offsets[k + 1] < offsets[k]) fail(`name ${k + 1}'s offset ${offsets[k + 1]} is before name ${k}'s`);
  }
  // The names decoded at once, in one pass, and cut at their offsets: a name's first character
  // is the count of UTF-16 units before its first byte (a byte starting a character counts one,
  // a 4-byte one two), found with one pass over the bytes when not all are ASCII.
  let text = null, units = offsets;
  const decode = () => {
    text = new TextDecoder('utf-8', { ignoreBOM: true }).decode(names);  // a name may start with U+FEFF
    if (text.length === nameBytes) return;
    units = new Uint32Array(m + p + 1);
    let k = 0, u = 0;
    for (let b = 0; b <= nameBytes; ++b) {
      while (k <= m + p && offsets[k] === b) units[k++] = u;
      const c = names[b];
      if ((c & 0xc0) !== 0x80) u += c >= 0xf0 ? 2 : 1;
    }
  };
  const nameOf = (k) => {
    if (text === null) decode();
    return text.slice(units[k], units[k + 1]);
  };
  return makeMap({ id, bounds, positions, lengths, diameters, from, to, slots, exits,
                   manholeName: (i) => nameOf(i), pipeName: (i) => nameOf(m + i) });
}

// The server's JSON document of columns (map_geometry.h) as the same map.
export function loadGeometry(g) {
  const mh = g.manholes, pp = g.pipes, n = mh.name.length;
  const positions = new Float64Array(2 * n);
  for (let i = 0; i < n; ++i) { positions[2 * i] = mh.x[i]; positions[2 * i + 1] = mh.y[i]; }
  const end = (a) => Uint32Array.from(a, (x) => (x < 0 ? kNone : x));
  return makeMap({ id: g.id, bounds: g.bounds, positions, lengths: Float64Array.from(pp.length_m),
                   diameters: Float64Array.from(pp.diameter_m), from: end(pp.from), to: end(pp.to),
                   slots: Uint16Array.from(mh.slots), exits: Uint8Array.from(mh.exit),
                   manholeName: (i) => mh.name[i], pipeName: (i) => pp.name[i] });
}

function makeMap(c) {
  const m = c.exits.length, p = c.lengths.length;
  const ends = new Float64Array(4 * p), openEnd = new Uint8Array(p), placeless = [];
  const pos = c.positions;
  for (let i = 0; i < p; ++i) {
    const a = c.from[i], b = c.to[i];
    openEnd[i] = a === kNone || b === kNone ? 1 : 0;
    if (a === kNone && b === kNone) {  // no position: not drawn
      ends.fill(NaN, 4 * i, 4 * i + 4);
      placeless.push(i);
      continue;
    }
    const known = a !== kNone ? a : b;
    const sx = pos[2 * known] + Math.max(c.lengths[i] / 10, 0.5);  // an open end's stub
    ends[4 * i] = a !== kNone ? pos[2 * a] : sx;
    ends[4 * i + 1] = pos[2 * (a !== kNone ? a : known) + 1];
    ends[4 * i + 2] = b !== kNone ? pos[2 * b] : sx;
    ends[4 * i + 3] = pos[2 * (b !== kNone ? b : known) + 1];
  }
  const isPlaceless = (i) => c.from[i] === kNone && c.to[i] === kNone;
  const pipe = (i) => ({ i, name: c.pipeName(i), from: [ends[4 * i], ends[4 * i + 1]], to: [ends[4 * i + 2], ends[4 * i + 3]],
                         openEnd: openEnd[i] === 1, placeless: isPlaceless(i), length_m: c.lengths[i],
                         diameter_m: c.diameters[i] });
  const manhole = (i) => ({ i, name: c.manholeName(i), position: [pos[2 * i], pos[2 * i + 1]], slots: c.slots[i],
                            exit: c.exits[i] === 1 });
  const once = (make) => { let v = null; return () => (v ??= make()); };
  const pipes = once(() => Array.from({ length: p }, (_, i) => pipe(i)));
  const manholes = once(() => Array.from({ length: m }, (_, i) => manhole(i)));
  // name -> index, read from the name table the first time a name is looked up (no object made);
  // byName's get(name) makes the one object asked for.
  const indexOf = (count, nameOf) => once(() => {
    const index = new Map();
    for (let i = 0; i < count; ++i) index.set(nameOf(i), i);
    return index;
  });
  const pipeIndex = indexOf(p, c.pipeName), manholeIndex = indexOf(m, c.manholeName);
  const byName = (index, make) => ({
    has: (name) => index().has(name),
    get: (name) => { const i = index().get(name); return i === undefined ? undefined : make(i); },
  });
  const pipeByName = byName(pipeIndex, pipe), manholeByName = byName(manholeIndex, manhole);
  return {
    id: c.id, bounds: c.bounds, manholeCount: m, pipeCount: p, openEnd, placeless: Uint32Array.from(placeless),
    columns: { ends, diameters: c.diameters, positions: pos, exits: c.exits, slots: c.slots },
    ends: { from: c.from, to: c.to },  // each pipe's manholes (indices; 0xffffffff: an open end)
    pipe,
    manhole,
    get pipes() { return pipes(); },
    get manholes() { return manholes(); },
    pipeIndex: (name) => pipeIndex().get(name),
    pipeByName,
    manholeByName,
  };
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
  if (place.pipe && map.pipeByName.has(place.pipe)) {
    const pipe = map.pipeByName.get(place.pipe);
    return pipe.placeless ? null : pointOnPipe(pipe, place.offset_m);
  }
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
