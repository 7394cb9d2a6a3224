// SPDX-License-Identifier: MIT
// The server's JSON API (docs/operator-station.md). The token, if the station was started with
// one, comes from the page's own URL (?token=...), as `sewerplan serve` prints it.
const token = new URLSearchParams(location.search).get('token');
const headers = token ? { Authorization: `Bearer ${token}` } : {};

async function call(path, options = {}) {
  const response = await fetch(path, { ...options, headers: { ...headers, ...options.headers } });
  const body = await response.json();
  if (!response.ok) throw Object.assign(new Error(body.error?.message ?? response.statusText), { body });
  return body;
}

const map = (id) => `api/maps/${encodeURIComponent(id)}`;
export const listMaps = () => call('api/maps');
export const uploadMap = (name, text) =>
  call(`api/maps?name=${encodeURIComponent(name)}`, { method: 'POST', body: text });
export const mapGeometry = (id) => call(map(id));
export const driveability = (id, profile) => call(`${map(id)}/driveability?profile=${encodeURIComponent(profile)}`);
export const validate = (id, mission) => call(`${map(id)}/validate`, { method: 'POST', body: JSON.stringify(mission) });
export const plan = (id, mission, timeLimit) =>
  call(`${map(id)}/plan?time_limit=${timeLimit}`, { method: 'POST', body: JSON.stringify(mission) });
export const replay = (id, log) => call(`${map(id)}/replay`, { method: 'POST', body: log });

export const campaignStatus = () => call('api/campaign');
export const cancelCampaign = () => call('api/campaign/cancel', { method: 'POST' });
export const campaignRun = (index, policy = 'ours') =>
  call(`api/campaign/runs/${index}?policy=${encodeURIComponent(policy)}`);

// Posts `body` and reads the answer's server-sent events as they arrive: onEvent(type, data,
// {wall_ms, received_ms}); wall_ms is the server's clock when it sent the event (if it says),
// received_ms the page's. A 4xx answer throws its error's message.
async function stream(path, body, onEvent, signal) {
  const response = await fetch(path, { method: 'POST', body: JSON.stringify(body), headers, signal });
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
export const simulate = (id, body, onEvent, signal) => stream(`${map(id)}/simulate`, body, onEvent, signal);
// Runs a fault campaign: "start", a "progress" per run, then "summary".
export const campaign = (id, body, onEvent, signal) => stream(`${map(id)}/campaign`, body, onEvent, signal);
