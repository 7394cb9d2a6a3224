// SPDX-License-Identifier: MIT
// The GeoJSON export (the Export GeoJSON button): the network with the mission, the route of the
// last plan made with the Plan button, and the trace of the last run (a simulation, a replayed log
// or a campaign run), in WGS84 for QGIS over a street map. The server writes it as
// `sewerplan export-geojson --mission M --plan PLAN --log EVENTS` does (POST /api/maps/ID/geojson,
// server/geojson_export.h): the page sends the plan's text and the run's events as the event log's
// lines, nothing drawn or computed here. A map without a CRS cannot be placed on the earth: the
// server says so, and the page shows it.
import * as api from './api.js';

// The request's body: the mission, the plan's text if a plan was made for it, the run's events
// (the executor's, not the page's own "route" and "report") as an event log.
export function exportBody(state) {
  const body = { mission: state.mission };
  if (state.planText) body.plan = state.planText;
  const log = state.events.filter((e) => e.type !== 'route' && e.type !== 'report');
  if (log.length > 0) body.log = log.map((e) => JSON.stringify(e)).join('\n');
  return body;
}

// Asks the server for the GeoJSON and saves it as MAP.geojson; returns what it holds, in words.
export async function exportGeoJson(state) {
  const text = await api.geojson(state.map.id, exportBody(state));
  const url = URL.createObjectURL(new Blob([text], { type: 'application/geo+json' }));
  const a = Object.assign(document.createElement('a'), { href: url, download: `${state.map.id}.geojson` });
  a.click();
  URL.revokeObjectURL(url);
  const layers = new Set(JSON.parse(text).features.map((f) => f.properties.layer));
  return `exported ${state.map.id}.geojson: ${[...layers].join(', ')}`;
}
