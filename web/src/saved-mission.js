// SPDX-License-Identifier: MIT
// The mission kept across a reload: after every edit the mission is saved in the browser's
// localStorage under the map's ID, with what identifies that map (its manhole and pipe counts and
// bounds); opening the map again restores it. A map's ID is its file's stem, so another map can
// come under the same ID (the server restarted with another file): a saved mission whose map
// differs, or that names a pipe, manhole or point the open map lacks, is stale; it is dropped, with
// a message saying why, rather than shown on a network it does not belong to.
//
//   saveMission(map, mission);
//   const { mission, message } = restoreMission(map);   // mission: null if none or stale

const key = (id) => `sewerplan-mission:${id}`;
const fingerprint = (map) => ({ manholes: map.manholeCount, pipes: map.pipeCount, bounds: [...map.bounds] });
const sameMap = (a, b) => a.manholes === b.manholes && a.pipes === b.pipes &&
  a.bounds.length === 4 && a.bounds.every((v, k) => v === b.bounds[k]);

export function saveMission(map, mission, storage = globalThis.localStorage) {
  try {
    storage.setItem(key(map.id), JSON.stringify({ map: fingerprint(map), saved: new Date().toISOString(), mission }));
  } catch {
    // Storage full or refused (a private window): the mission is simply not kept.
  }
}

export function forgetMission(map, storage = globalThis.localStorage) {
  storage.removeItem(key(map.id));
}

// The places a mission names: its start, each task's place or pipe. An inspection point's name is
// not checked here (the page's geometry has none; the server's validation names it).
function namesIn(mission) {
  const places = [mission.start, ...(mission.tasks ?? []).map((t) => t.at ?? { pipe: t.pipe })].filter(Boolean);
  return places.map((p) => (p.pipe !== undefined ? ['pipe', p.pipe] : p.manhole !== undefined ? ['manhole', p.manhole]
                                                                                              : ['point', p.point]));
}

export function restoreMission(map, storage = globalThis.localStorage) {
  let saved = null;
  try {
    saved = JSON.parse(storage.getItem(key(map.id)));
  } catch {
    saved = { broken: true };
  }
  if (!saved) return { mission: null, message: '' };
  const drop = (why) => {
    storage.removeItem(key(map.id));
    return { mission: null, message: `The mission saved for map ${map.id}${saved.saved ? ` on ${saved.saved}` : ''} was dropped: ${why}` };
  };
  const m = saved.mission;
  if (saved.broken || !m || m.format !== 'sewerplan-mission' || !Array.isArray(m.tasks) || !saved.map) {
    return drop('it is not a readable mission');
  }
  if (!sameMap(saved.map, fingerprint(map))) {
    return drop(`it was for another map of that ID (${saved.map.manholes} manholes, ${saved.map.pipes} pipes; ` +
                `this one has ${map.manholeCount} and ${map.pipeCount})`);
  }
  const missing = namesIn(m).find(([kind, name]) =>
    (kind === 'pipe' && !map.pipeByName.has(name)) || (kind === 'manhole' && !map.manholeByName.has(name)));
  if (missing) return drop(`it names ${missing[0]} ${missing[1]}, which this map lacks`);
  return { mission: m, message: '' };
}
