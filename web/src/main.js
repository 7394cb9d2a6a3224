// SPDX-License-Identifier: MIT
// The operator station's page: the map in its own coordinates (deck.gl, an orthographic view on
// WebGL: no tiles), a mission clicked onto it, the plan and a simulation streamed from the server.
import { Deck, OrthographicView } from '@deck.gl/core';
import { LineLayer, ScatterplotLayer, TextLayer } from '@deck.gl/layers';
import * as api from './api.js';

const $ = (id) => document.getElementById(id);
const state = { map: null, blocked: new Map(), mission: null, route: new Set(), robot: null };

const deck = new Deck({
  parent: $('view'),
  views: new OrthographicView({ flipY: false }),
  controller: { doubleClickZoom: false },  // clicks place tasks: none may zoom
  initialViewState: { target: [0, 0, 0], zoom: 0 },
  getCursor: ({ isHovering }) => (isHovering ? 'pointer' : 'grab'),
  onHover: (info) => showHover(info),
  onClick: (info) => clickPipe(info),
  layers: [],
});

// Columns of the geometry document -> one object per pipe and manhole, for deck.gl's accessors.
function loadGeometry(g) {
  const m = g.manholes;
  const manholes = m.name.map((name, i) => ({ i, name, position: [m.x[i], m.y[i]], slots: m.slots[i],
                                              exit: m.exit[i] === 1 }));
  const p = g.pipes;
  const pipes = [];
  p.name.forEach((name, i) => {
    const a = p.from[i], b = p.to[i];
    if (a < 0 || b < 0) return;  // an open end: not drawn in this slice
    pipes.push({ i, name, from: manholes[a].position, to: manholes[b].position,
                 length_m: p.length_m[i], diameter_m: p.diameter_m[i] });
  });
  return { id: g.id, name: g.name, bounds: g.bounds, manholes, pipes,
           pipeByName: new Map(pipes.map((x) => [x.name, x])) };
}

function fitView(bounds) {
  const [x0, y0, x1, y1] = bounds;
  const view = $('view');
  const size = Math.max(x1 - x0, y1 - y0, 1);
  const zoom = Math.log2(Math.min(view.clientWidth, view.clientHeight) / (size * 1.1));
  deck.setProps({ initialViewState: { target: [(x0 + x1) / 2, (y0 + y1) / 2, 0], zoom } });
}

function render() {
  const map = state.map;
  if (!map) return;
  const taskPipes = new Map(state.mission.tasks.map((t) => [t.pipe ?? t.at?.pipe, t]));
  const layers = [
    new LineLayer({
      id: 'pipes', data: map.pipes, pickable: true,
      getSourcePosition: (p) => p.from, getTargetPosition: (p) => p.to,
      getColor: (p) => (state.route.has(p.name) ? [230, 120, 0] : state.blocked.has(p.name)
                        ? [200, 40, 40] : [60, 90, 160]),
      getWidth: (p) => (state.route.has(p.name) ? 6 : 1 + 4 * Math.min(p.diameter_m, 1)),
      widthUnits: 'pixels',
      updateTriggers: { getColor: [state.route, state.blocked], getWidth: [state.route] },
    }),
    new ScatterplotLayer({
      id: 'manholes', data: map.manholes, pickable: true,
      getPosition: (m) => m.position, radiusUnits: 'pixels',
      getRadius: (m) => (m.exit ? 6 : 3 + Math.min(m.slots, 4) * 0.5),
      getFillColor: (m) => (m.exit ? [20, 150, 60] : [90, 90, 90]),
    }),
    new ScatterplotLayer({
      id: 'tasks', data: [...taskPipes.entries()].filter(([pipe]) => map.pipeByName.has(pipe)),
      getPosition: ([pipe, t]) => pointOnPipe(map.pipeByName.get(pipe), t.at?.offset_m),
      radiusUnits: 'pixels', getRadius: 7, getFillColor: [240, 200, 0], stroked: true,
      getLineColor: [0, 0, 0], lineWidthUnits: 'pixels', getLineWidth: 1,
    }),
  ];
  if (map.manholes.length <= 2000) {  // names at every zoom only on small maps
    layers.push(new TextLayer({ id: 'names', data: map.manholes, getPosition: (m) => m.position,
                                getText: (m) => m.name, getSize: 11, getPixelOffset: [0, -12] }));
  }
  if (state.robot) {
    layers.push(new ScatterplotLayer({ id: 'robot', data: [state.robot], getPosition: (r) => r,
                                       radiusUnits: 'pixels', getRadius: 9,
                                       getFillColor: [220, 0, 120] }));
  }
  deck.setProps({ layers });
}

function pointOnPipe(pipe, offset) {
  const t = offset === undefined ? 0.5 : Math.max(0, Math.min(1, offset / pipe.length_m));
  return [pipe.from[0] + t * (pipe.to[0] - pipe.from[0]), pipe.from[1] + t * (pipe.to[1] - pipe.from[1])];
}

// The clicked offset along the pipe, from its `from` end, in metres of the pipe's length.
function offsetOf(pipe, [x, y]) {
  const dx = pipe.to[0] - pipe.from[0], dy = pipe.to[1] - pipe.from[1];
  const t = ((x - pipe.from[0]) * dx + (y - pipe.from[1]) * dy) / (dx * dx + dy * dy || 1);
  return Math.round(Math.max(0, Math.min(1, t)) * pipe.length_m * 100) / 100;
}

function showHover(info) {
  const box = $('hover');
  if (!info.object || !info.layer || !['pipes', 'manholes'].includes(info.layer.id)) {
    box.style.display = 'none';
    return;
  }
  const o = info.object;
  const reason = state.blocked.get(o.name);
  box.textContent = info.layer.id === 'pipes'
    ? `pipe ${o.name}, ${o.length_m.toFixed(1)} m, ⌀ ${o.diameter_m.toFixed(2)} m${reason ? ` — ${reason}` : ''}`
    : `manhole ${o.name}${o.exit ? ' (exit)' : ''}`;
  Object.assign(box.style, { display: 'block', left: `${info.x + 12}px`, top: `${info.y + 12}px` });
}

function clickPipe(info) {
  if (!info.object || info.layer?.id !== 'pipes') return;
  const pipe = info.object;
  const offset = offsetOf(pipe, info.coordinate);
  const mode = document.querySelector('input[name=mode]:checked').value;
  const m = state.mission;
  const n = m.tasks.filter((t) => !t.final).length + 1;
  if (mode === 'start') m.start = { pipe: pipe.name, offset_m: offset };
  if (mode === 'sample') {
    m.tasks.splice(endIndex(), 0, { name: `sample-${n}`, type: 'take_water_sample',
                                    at: { pipe: pipe.name, offset_m: offset } });
  }
  if (mode === 'inspect') {
    m.tasks.splice(endIndex(), 0, { name: `inspect-${n}`, type: 'inspect_pipe', pipe: pipe.name });
  }
  if (mode === 'end') {
    m.tasks = m.tasks.filter((t) => !t.final);
    m.tasks.push({ name: 'end', type: 'go_to', at: { pipe: pipe.name, offset_m: offset }, final: true });
  }
  missionChanged();
}

const endIndex = () => {
  const i = state.mission.tasks.findIndex((t) => t.final);
  return i < 0 ? state.mission.tasks.length : i;
};

const describePlace = (p) => (p ? `${p.pipe ?? p.manhole ?? p.point}${p.offset_m !== undefined ? ` at ${p.offset_m} m` : ''}` : '—');

async function missionChanged() {
  const m = state.mission;
  m.profile = $('profile').value;
  $('mission-summary').textContent = `start: ${describePlace(m.start)}`;
  $('tasks').replaceChildren(...m.tasks.map((t, i) => {
    const li = document.createElement('li');
    li.textContent = `${t.name}: ${t.type} ${t.pipe ?? describePlace(t.at)} `;
    const remove = document.createElement('button');
    remove.textContent = '×';
    remove.onclick = () => { m.tasks.splice(i, 1); missionChanged(); };
    li.append(remove);
    return li;
  }));
  render();
  if (!m.start || m.tasks.length === 0) return;
  const verdict = await api.validate(state.map.id, m);
  $('messages').textContent = verdict.errors.map((e) => `${e.where}: ${e.message}`).join('\n');
}

async function openMap(id) {
  state.map = loadGeometry(await api.mapGeometry(id));
  state.mission = { format: 'sewerplan-mission', version: 1, name: 'station', tasks: [] };
  state.route = new Set();
  state.robot = null;
  fitView(state.map.bounds);
  await loadDriveability();
  missionChanged();
}

// The pipes the profile cannot drive, with the reasons of `info --profile`.
async function loadDriveability() {
  const r = await api.driveability(state.map.id, $('profile').value);
  state.blocked = new Map([
    ...r.too_narrow.map((p) => [p, `too narrow for ${r.profile}`]),
    ...r.too_wide.map((p) => [p, `too wide for ${r.profile}`]),
    ...r.cut_off_by_findings.pipes.map((p) => [p, 'cut off by inspection findings']),
  ]);
  render();
}

async function runPlan() {
  $('messages').textContent = '';
  try {
    const result = await api.plan(state.map.id, state.mission, $('time-limit').value);
    state.route = new Set(result.steps.flatMap((s) => [s.pipe, s.from_pipe, s.to_pipe]).filter(Boolean));
    $('plan-summary').textContent =
      `${result.steps.length} steps, ${result.cost_s.toFixed(1)} s, ${result.energy_wh.toFixed(1)} Wh; ` +
      `${result.decision}; ${result.algorithm}${result.motion_table ? '; motion table' : ''}`;
    $('steps').replaceChildren(...result.steps.map((s, i) => {
      const li = document.createElement('li');
      li.textContent = s.action;
      li.title = result.fused[i]?.text ?? '';
      return li;
    }));
    $('dropped').replaceChildren(...result.dropped.map((d) => {
      const li = document.createElement('li');
      li.textContent = `${d.task}: ${d.reason}`;
      return li;
    }));
    render();
  } catch (e) {
    $('messages').textContent = e.message;
  }
}

// Where an event puts the robot, if it says: a failure's pipe and offset, or the first pipe or
// manhole named by the action it starts (its parameters as fusion prints them).
function robotAt(event) {
  if (event.pipe && state.map.pipeByName.has(event.pipe)) {
    return pointOnPipe(state.map.pipeByName.get(event.pipe), event.offset_m);
  }
  if (typeof event.parameters !== 'string') return null;
  for (const word of event.parameters.split(/[\s,()]+/)) {
    if (state.map.pipeByName.has(word)) return pointOnPipe(state.map.pipeByName.get(word));
    const manhole = state.map.manholes.find((m) => m.name === word);
    if (manhole) return manhole.position;
  }
  return null;
}

let running = null;
async function runSimulation() {
  running?.abort();  // a new run cancels the last one's stream, and the server halts it
  running = new AbortController();
  $('events').replaceChildren();
  const body = { mission: state.mission };
  if ($('faults').value.trim()) body.random_faults = $('faults').value.trim();
  try {
    await api.simulate(state.map.id, body, (type, data) => {
      const li = document.createElement('li');
      li.textContent = `${(data.t_s ?? 0).toFixed(1)} s ${type} ${JSON.stringify(data).slice(0, 160)}`;
      $('events').append(li);
      li.scrollIntoView({ block: 'nearest' });
      const at = robotAt(data);
      if (at) { state.robot = at; render(); }
    }, running.signal);
  } catch (e) {
    if (e.name !== 'AbortError') $('messages').textContent = e.message;
  }
}

async function start() {
  const { maps, profiles } = await api.listMaps();
  $('map').replaceChildren(...maps.map((m) => new Option(`${m.id} (${m.manholes} manholes)`, m.id)));
  $('profile').replaceChildren(...profiles.map((p) => new Option(p, p)));
  $('map').onchange = () => openMap($('map').value);
  $('profile').onchange = () => { loadDriveability(); missionChanged(); };
  $('plan').onclick = runPlan;
  $('simulate').onclick = runSimulation;
  if (maps.length > 0) await openMap(maps[0].id);
  document.body.dataset.ready = 'true';
}

start();

// For the browser test (e2e/): the state, and where a pipe's point is on the screen.
window.station = {
  state,
  screenPoint(name, fraction) {
    const pipe = state.map.pipeByName.get(name);
    const viewport = deck.getViewports()[0];
    return viewport.project(pointOnPipe(pipe, fraction * pipe.length_m));
  },
};
