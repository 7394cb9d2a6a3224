// SPDX-License-Identifier: MIT
// The server's JSON API (docs/server.md). The token, if the station was started with one, comes
// from the page's own URL (?token=...), as `sewerplan serve` prints it.
const token = new URLSearchParams(location.search).get('token');
const headers = token ? { Authorization: `Bearer ${token}` } : {};

async function call(path, options = {}) {
  const response = await fetch(path, { ...options, headers: { ...headers, ...options.headers } });
  const body = await response.json();
  if (!response.ok) throw Object.assign(new Error(body.error?.message ?? response.statusText), { body });
  return body;
}

export const listMaps = () => call('api/maps');
export const mapGeometry = (id) => call(`api/maps/${encodeURIComponent(id)}`);
export const driveability = (id, profile) =>
  call(`api/maps/${encodeURIComponent(id)}/driveability?profile=${encodeURIComponent(profile)}`);
export const validate = (id, mission) =>
  call(`api/maps/${encodeURIComponent(id)}/validate`, { method: 'POST', body: JSON.stringify(mission) });
export const plan = (id, mission, timeLimit) =>
  call(`api/maps/${encodeURIComponent(id)}/plan?time_limit=${timeLimit}`,
       { method: 'POST', body: JSON.stringify(mission) });

// Runs a simulation; onEvent(type, data) for every server-sent event as it arrives.
export async function simulate(id, body, onEvent, signal) {
  const response = await fetch(`api/maps/${encodeURIComponent(id)}/simulate`,
                               { method: 'POST', body: JSON.stringify(body), headers, signal });
  if (!response.ok) {
    const error = await response.json();
    throw Object.assign(new Error(error.error?.message ?? response.statusText), { body: error });
  }
  const reader = response.body.pipeThrough(new TextDecoderStream()).getReader();
  let buffer = '';
  for (;;) {
    const { value, done } = await reader.read();
    if (done) break;
    buffer += value;
    let end;
    while ((end = buffer.indexOf('\n\n')) >= 0) {
      const block = buffer.slice(0, end);
      buffer = buffer.slice(end + 2);
      const type = /^event: (.*)$/m.exec(block)?.[1];
      const data = /^data: (.*)$/m.exec(block)?.[1];
      if (type && data) onEvent(type, JSON.parse(data));
    }
  }
}
