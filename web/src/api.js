// SPDX-License-Identifier: MIT
// The server's JSON API (docs/operator-station.md).
//
// The token, if the station was started with one: `sewerplan serve` prints the page's address with
// it in the fragment (#token=T), which a browser never sends to a server. The page keeps it for
// this tab (sessionStorage: a reload works) and takes it out of the address bar and the history.
// Every request sends it as "Authorization: Bearer T", the streams too (read with fetch(), not
// EventSource, which cannot set a header); the server refuses a ?token= in a URL.
const TOKEN_KEY = 'sewerplan-token';
function readToken() {
  const fragment = new URLSearchParams(location.hash.slice(1));
  const token = fragment.get('token');
  if (token === null) return sessionStorage.getItem(TOKEN_KEY);
  sessionStorage.setItem(TOKEN_KEY, token);
  fragment.delete('token');
  const rest = fragment.toString();
  history.replaceState(null, '', `${location.pathname}${location.search}${rest ? `#${rest}` : ''}`);
  return token;
}
const token = readToken();
const headers = token ? { Authorization: `Bearer ${token}` } : {};
// The server refuses a POST of a type any web page may send to any site unasked (text/plain, a
// form, none): JSON goes as application/json, a file the operator uploads as it is, as
// application/octet-stream (docs/operator-station.md, "Who may drive the station").
const json = { 'Content-Type': 'application/json' };
const file = { 'Content-Type': 'application/octet-stream' };

async function call(path, options = {}) {
  const response = await fetch(path, { ...options, headers: { ...headers, ...options.headers } });
  const body = await response.json();
  if (!response.ok) throw Object.assign(new Error(body.error?.message ?? response.statusText), { body, status: response.status });
  return body;
}

const map = (id) => `api/maps/${encodeURIComponent(id)}`;
// Whether driveability, plans, simulations and campaigns use the map's motion table, when it has
// one (the server's default; false: ?motion=0, the CLI's --no-motion).
// What plans and simulations make of the map's inspection findings (the CLI's --risk: impassable,
// the server's default, avoid, expected or ignore).
export const settings = { motion: true, risk: 'impassable' };
const motion = (path) => (settings.motion ? path : `${path}${path.includes('?') ? '&' : '?'}motion=0`);
const risk = (path) => `${path}${path.includes('?') ? '&' : '?'}risk=${encodeURIComponent(settings.risk)}`;
export const listMaps = () => call('api/maps');
export const uploadMap = (name, text) =>
  call(`api/maps?name=${encodeURIComponent(name)}`, { method: 'POST', body: text, headers: file });
// The map's compact geometry (typed arrays, geometry.js's readGeometry) as an ArrayBuffer.
export async function mapGeometry(id) {
  const response = await fetch(`${map(id)}/geometry`, { headers });
  if (!response.ok) {
    const body = await response.json();
    throw Object.assign(new Error(body.error?.message ?? response.statusText), { body });
  }
  return response.arrayBuffer();
}
export const uploadCondition = (id, name, text) =>
  call(`${map(id)}/condition?name=${encodeURIComponent(name)}`, { method: 'POST', body: text, headers: file });
// The profile's driveability, in two steps: the promise resolves when the answer has come, with a
// function that reads its JSON (and throws the server's error). A large answer asked early is
// parsed only when the page has time for it: main.js reads it after the map's first draw. An
// aborted `signal` (a later request made this one outdated) stops the request or its body's read.
export async function driveability(id, profile, signal) {
  const response = await fetch(motion(`${map(id)}/driveability?profile=${encodeURIComponent(profile)}`), { headers, signal });
  return async () => {
    const body = await response.json();
    if (!response.ok) throw Object.assign(new Error(body.error?.message ?? response.statusText), { body });
    return body;
  };
}
// The map's inspection findings for a profile, with what the risk mode makes of them.
export const findings = (id, profile, signal) =>
  call(risk(`${map(id)}/findings?profile=${encodeURIComponent(profile)}`), { signal });
// The basemap's tiles for a view of the map (basemap.js): each with its corners in the map's metres.
export const basemap = (id, [x0, y0, x1, y1], mpp) =>
  call(`${map(id)}/basemap?x0=${x0}&y0=${y0}&x1=${x1}&y1=${y1}&mpp=${mpp}`);
// A basemap tile's image: the station's own (`--tiles DIR`: with the token, as every API request),
// or another server's (an XYZ URL: never with the token, and only if that server lets other sites'
// pages read its tiles, CORS, as the public tile servers do).
export async function tile(url, kind) {
  const response = await fetch(url, kind === 'directory' ? { headers } : { mode: 'cors', credentials: 'omit' });
  if (!response.ok) throw new Error(`${response.status} ${response.statusText}`.trim());
  return createImageBitmap(await response.blob());
}
export const validate = (id, mission) => call(`${map(id)}/validate`, { method: 'POST', body: JSON.stringify(mission), headers: json });
export const plan = (id, mission, timeLimit) =>
  call(risk(motion(`${map(id)}/plan?time_limit=${timeLimit}`)), { method: 'POST', body: JSON.stringify(mission), headers: json });
export const replay = (id, log) => call(`${map(id)}/replay`, { method: 'POST', body: log, headers: file });
// The network, the mission, a plan's route and a run's trace as GeoJSON text (export-geojson.js).
export async function geojson(id, body) {
  const response = await fetch(`${map(id)}/geojson`, { method: 'POST', body: JSON.stringify(body), headers: { ...headers, ...json } });
  if (!response.ok) {
    const error = await response.json();
    throw Object.assign(new Error(error.error?.message ?? response.statusText), { body: error });
  }
  return response.text();
}

export const campaignStatus = () => call('api/campaign');
export const cancelCampaign = () => call('api/campaign/cancel', { method: 'POST', headers: json });
export const campaignRun = (index, policy = 'ours') =>
  call(`api/campaign/runs/${index}?policy=${encodeURIComponent(policy)}`);

// Posts `body` and reads the answer's server-sent events as they arrive: onEvent(type, data,
// {wall_ms, received_ms}); wall_ms is the server's clock when it sent the event (if it says),
// received_ms the page's. A 4xx answer throws its error's message.
async function stream(path, body, onEvent, signal) {
  const response = await fetch(path, { method: 'POST', body: JSON.stringify(body), headers: { ...headers, ...json }, signal });
  if (!response.ok) {
    const error = await response.json();
    throw Object.assign(new Error(error.error?.message ?? response.statusText), { body: error });
  }
  const reader = response.body.pipeThrough(new TextDecoderStream()).getReader();
  let buffer = '';
  for (;;) {
    const { value, done } = await reader.read();
    if (done) break;
    const received = Date.now();
    buffer += value;
    let end;
    while ((end = buffer.indexOf('\n\n')) >= 0) {
      const block = buffer.slice(0, end);
      buffer = buffer.slice(end + 2);
      const type = /^event: (.*)$/m.exec(block)?.[1];
      const data = /^data: (.*)$/m.exec(block)?.[1];
      const wall = /^wall_ms: (\d+)$/m.exec(block)?.[1];
      if (type && data) onEvent(type, JSON.parse(data), { wall_ms: wall ? Number(wall) : null, received_ms: received });
    }
  }
}

// Runs a simulation: the executor's events, each plan's route, then the report.
export const simulate = (id, body, onEvent, signal) => stream(risk(motion(`${map(id)}/simulate`)), body, onEvent, signal);
// Runs a fault campaign: "start", a "progress" per run, then "summary".
export const campaign = (id, body, onEvent, signal) => stream(motion(`${map(id)}/campaign`), body, onEvent, signal);
