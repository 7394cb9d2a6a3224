// SPDX-License-Identifier: MIT
// The operator station's page: wires the map view (map-view.js), the mission editor (mission.js),
// the hidden faults (faults.js), the plan view (plan-view.js), the event player (player.js) and the
// campaign panel (campaign.js) to the server's API (api.js), with the GIS habits (search-box.js,
// undo.js, task-keys.js, scale-bar.js, cursor-coords.js, saved-mission.js, export-geojson.js;
// docs/operator-station.md). All state is here, in `state`.
import * as api from './api.js';
import { Basemap } from './basemap.js';
import { CampaignPanel } from './campaign.js';
import { trackCursor } from './cursor-coords.js';
import { exportGeoJson } from './export-geojson.js';
import { clickFault, isEmpty, newFaults, renderFaults } from './faults.js';
import { offsetOf, pipesOfSteps, placePoint, readGeometry } from './geometry.js';
import { mapRequests } from './latest.js';
import { createMapView } from './map-view.js';
import { clickMission, describePlace, download, newMission, renderTasks } from './mission.js';
import { showFatal } from './fatal.js';
import { outcomeLine } from './outcome.js';
import { PlanHistory } from './plan-history.js';
import { actionTarget, Player, wherePoint } from './player.js';
import { describeFinding, findingAt, placeFindings } from './findings-layer.js';
import { learntGeoJson, learntPlaces } from './learnt-layer.js';
import { renderLegend } from './legend.js';
import { renderPlanRisk } from './plan-risk.js';
import { planOrder } from './task-markers.js';
import { restoreMission, saveMission } from './saved-mission.js';
import { showScale } from './scale-bar.js';
import { findPlace, suggestions, viewOf } from './search-box.js';
import { bindEditorKeys, TaskSelection } from './task-keys.js';
import { EditHistory } from './undo.js';
import { renderWarnings } from './warnings.js';

const $ = (id) => document.getElementById(id);
const state = {
  map: null, blocked: new Map(), mission: null, faults: newFaults(), route: new Set(), oldRoutes: [],
  failures: [], robot: null, beacon: false, dropped: new Set(), done: new Set(), events: [], outcome: null,
  delays_ms: [], highlight: null, mapInfo: new Map(), planText: null,
  findings: [], learnt: [], learntDoc: null, planOrder: new Map(),  // findings-layer.js, learnt-layer.js
};
const history = new EditHistory();  // the mission's edits (undo.js)

let basemap = null;  // the optional basemap (basemap.js), once the server said its source
const view = createMapView($('view'), {
  onClick: (info) => clickMap(info), onHover: (info) => showHover(info),
  onViewChange: (v) => { showScale($('scale-bar'), $('scale-text'), v.zoom); askBasemap(); },
  underlay: (g, toScreen) => basemap?.draw(g, toScreen),
});
// The basemap's tiles for the view, if it is on (basemap.js asks nothing otherwise).
const askBasemap = () => basemap?.view(view.rect(), 2 ** -view.viewState().zoom);
const draw = () => view.draw(state);
// The Plan panel: the plan asked, or a run's plan and replans; one chosen is highlighted.
const plans = new PlanHistory({ onChange: () => { state.highlight = plans.highlighted(); draw(); } });

function showHover(info) {
  const box = $('hover');
  const finding = findingAt(state.findings, info.coordinate, view.viewState().zoom);
  if (finding) {  // a finding is drawn over its pipe: it is what the pointer is on
    box.textContent = `finding ${describeFinding(finding)}`;
    Object.assign(box.style, { display: 'block', left: `${info.x + 12}px`, top: `${info.y + 12}px` });
    return;
  }
  if (!info.object || !['pipes', 'manholes'].includes(info.layer?.id)) {
    box.style.display = 'none';
    return;
  }
  const o = info.object;
  const reason = state.blocked.get(o.name);
  box.textContent = info.layer.id === 'pipes'
    ? `pipe ${o.name}, ${o.length_m.toFixed(1)} m, ⌀ ${o.diameter_m.toFixed(2)} m${o.openEnd ? ', open end' : ''}${reason ? ` — ${reason}` : ''}`
    : `manhole ${o.name}${o.exit ? ' (exit)' : ''}, ${o.slots} slots`;
  Object.assign(box.style, { display: 'block', left: `${info.x + 12}px`, top: `${info.y + 12}px` });
}

function clickMap(info) {
  const layer = info.layer?.id;
  if (!info.object || (layer !== 'pipes' && layer !== 'manholes')) return;
  const where = layer === 'pipes'
    ? { pipe: info.object.name, offset: offsetOf(info.object, info.coordinate) }
    : { manhole: info.object.name };
  const mode = document.querySelector('input[name=mode]:checked').value;
  if (clickFault(state.faults, mode, where)) faultsChanged();
  else if (clickMission(state.mission, mode, where)) missionChanged();
}

const taskStatus = (t) => (state.dropped.has(t.name) ? '— dropped' : state.done.has(t.name) ? '— done' : '');

async function missionChanged() {
  const m = state.mission;
  m.profile = $('profile').value;
  if (history.record(JSON.stringify(m))) state.planText = null;  // the last plan was for another mission
  showHistory();
  saveMission(state.map, m);
  state.planOrder = new Map();  // the last plan's numbers are for the mission it was made for
  $('mission-summary').textContent = `start: ${describePlace(m.start)}`;
  renderTasks($('tasks'), m, missionChanged, taskStatus);
  draw();
  if (!m.start || m.tasks.length === 0) return;
  const verdict = await api.validate(state.map.id, m);
  $('messages').textContent = verdict.errors.map((e) => `${e.where}: ${e.message}`).join('\n');
}

// Undo and redo (undo.js): the mission becomes the state recorded, its profile selected.
function restoreEdit(snapshot) {
  if (snapshot === null) return;
  state.mission = JSON.parse(snapshot);
  const profile = state.mission.profile;
  if (profile && [...$('profile').options].some((o) => o.value === profile)) $('profile').value = profile;
  missionChanged();
}
const undo = () => restoreEdit(history.undo());
const redo = () => restoreEdit(history.redo());
function showHistory() {
  $('undo').disabled = !history.canUndo;
  $('redo').disabled = !history.canRedo;
}
const selection = new TaskSelection($('tasks'), () => state.mission?.tasks ?? []);
// The Delete key: the selected task removed, as its × button does. Whether there was one.
function removeSelected() {
  const i = selection.index();
  if (i < 0) return false;
  state.mission.tasks.splice(i, 1);
  missionChanged();
  return true;
}
const fitView = () => state.map && view.fit(state.map.bounds, { now: true });

// The search box: the place named is centred, marked and its name said; else why not.
function search() {
  if (!state.map) return;
  const found = findPlace(state.map, $('search').value);
  $('search-note').textContent = found.error ?? `${found.kind} ${found.name}`;
  if (found.error) return;
  // Drawn as a warning's objects are (map-view.js), and named (the browser test reads it).
  state.highlight = { ...found, pipes: found.kind === 'pipe' ? [found.name] : [], manholes: found.kind === 'manhole' ? [found.name] : [] };
  view.setView(viewOf(found, $('view').clientWidth, $('view').clientHeight));
  draw();
}

function faultsChanged() {
  renderFaults($('faults'), state.faults, faultsChanged);
  draw();
}

// Opens a map: the profile's driveability is asked at once, beside the geometry (the server works
// on it while the page reads and draws the map), and applied when both it and the first draw are
// there: the map is not kept waiting for it (a 100,000-manhole map's takes the server seconds). A
// profile changed while the map opens asks for this map too (latest.js); the latest answer wins.
// Performance marks (`ID: ...`) time each phase for the browser test (e2e/), the driveability's
// too (come, read: its JSON, applied: the pipes classed, drawn).
async function openMap(id) {
  const t0 = performance.now();
  performance.mark(`${id}: asked`);
  delete state.timings.driveability_ms;  // the last map's
  delete state.timings.driveability_drawn_ms;
  const previous = state.map;
  const drawn = driveabilityRequests.opening(id);
  mapAskedAt = t0;
  showDriveability();
  let buffer;
  try {
    buffer = await api.mapGeometry(id);
  } catch (e) {
    if (driveabilityRequests.id === id && previous) {  // the last map stays open, as the selector says
      driveabilityRequests.opening(previous.id)();
      $('map').value = previous.id;
      showDriveability();  // its answer pending, if any, was dropped with the request for this map
    }
    throw e;
  }
  // Another map asked for meanwhile is the one to open: this one's geometry came too late.
  if (driveabilityRequests.id !== id) return;
  performance.mark(`${id}: geometry come`);
  state.timings.geometry_ms = Math.round(performance.now() - t0);  // fetched
  state.map = readGeometry(buffer, id);
  state.timings.load_geometry_ms = Math.round(performance.now() - t0) - state.timings.geometry_ms;
  state.blocked = new Map();
  state.findings = [];
  $('driveability').textContent = 'driveability: asking the server';
  // The mission kept for this map across a reload (saved-mission.js), unless it is stale.
  const kept = restoreMission(state.map);
  if (kept.mission && [...$('profile').options].some((o) => o.value === kept.mission.profile)) $('profile').value = kept.mission.profile;
  state.mission = kept.mission ?? newMission($('profile').value);
  $('messages').textContent = kept.message;
  history.reset(JSON.stringify(state.mission));
  state.planText = null;
  selection.reset();
  state.highlight = null;
  $('search-note').textContent = '';
  state.faults = newFaults();
  $('condition').textContent = '';
  $('placeless').textContent = placelessNote(state.map);
  showWarnings();
  clearRun();
  state.route = new Set();
  basemap?.setMap(id, state.mapInfo.get(id)?.crs ?? null);
  view.fit(state.map.bounds);
  missionChanged();
  faultsChanged();
  await afterDraw();
  if (driveabilityRequests.id !== id) return;  // another map is opening: it reports, not this one
  performance.mark(`${id}: first draw`);
  state.timings.open_map_ms = Math.round(performance.now() - t0);
  document.body.dataset.opened = id;
  askBasemap();
  loadFindings();
  drawn();  // the driveability asked meanwhile is applied now or when it comes (not awaited)
}

// A pipe with no manhole at either end has no position on the map (geometry.js): it is not drawn,
// so the page names such pipes (the first few) rather than leave them unseen.
function placelessNote(map) {
  const n = map.placeless.length;
  if (n === 0) return '';
  const shown = Array.from(map.placeless.subarray(0, 5), (i) => map.pipe(i).name);
  return `${n} pipe${n === 1 ? '' : 's'} with no manhole at either end, not drawn: ` +
         `${shown.join(', ')}${n > shown.length ? ', ...' : ''}`;
}

// Resolves after the map view has drawn the current layers (and the network's image, lod.js).
const afterDraw = () => view.whenDrawn();

// The driveability's requests, for the map being opened or open: only the latest one's answer is
// shown (latest.js), so an answer for a profile no longer selected, or for a map no longer open,
// is dropped.
const driveabilityRequests = mapRequests();

// The pipes the profile cannot drive, with the reasons of `info --profile`.
// With the map's motion table (unless unticked), as `info --profile`; the manhole passages the
// robot cannot take are counted beside the profile, those the table rejects apart. Asks the
// selected profile's for the map being opened or open; the first answer shown for a map is timed
// from when that map was asked (mapAskedAt).
let mapAskedAt = 0;
async function showDriveability() {
  let r, answer = null;
  try {
    answer = await driveabilityRequests.run((id, signal) => api.driveability(id, $('profile').value, signal));
    if (!answer) return;  // a later request, or another map opened meanwhile
    performance.mark(`${answer.id}: driveability come`);
    r = await answer.value();  // its JSON read now, not while the map was drawn
    if (!answer.latest()) return;
    performance.mark(`${answer.id}: driveability read`);
  } catch (e) {
    if (answer && !answer.latest()) return;
    $('driveability').textContent = e.message;
    state.blocked = new Map();
    draw();
    return;
  }
  const byTable = r.passages.filter((p) => p.motion_reason).length;
  $('driveability').textContent = `${r.passages.length} of ${r.passages_checked} manhole passages not drivable` +
    (r.motion_table ? ` (${byTable} by the motion table)` : '');
  $('driveability').title = r.passages.slice(0, 50).map((p) =>
    `${p.manhole} ${p.from_pipe} to ${p.to_pipe}: ${p.motion_reason ?? [p.turn_exceeded && `turn ${p.turn_deg.toFixed(0)} deg`, p.step_exceeded && `step ${p.step_m.toFixed(2)} m`].filter(Boolean).join(', ')}`).join('\n');
  state.blocked = new Map([
    ...r.too_narrow.map((p) => [p, `too narrow for ${r.profile}`]),
    ...r.too_wide.map((p) => [p, `too wide for ${r.profile}`]),
    ...r.cut_off_by_findings.pipes.map((p) => [p, 'cut off by inspection findings']),
  ]);
  draw();
  const id = answer.id;
  performance.mark(`${id}: driveability applied`);
  document.body.dataset.driveability = id;
  if (state.timings.driveability_ms !== undefined) return;
  const t0 = mapAskedAt;
  state.timings.driveability_ms = Math.round(performance.now() - t0);  // from the map asked to applied
  await afterDraw();
  if (!answer.latest()) return;
  performance.mark(`${id}: driveability drawn`);
  state.timings.driveability_drawn_ms = Math.round(performance.now() - t0);
}

// The driveability asked again (another profile, the motion table ticked or not).
const loadDriveability = () => showDriveability();

// A plan: the last one's route, steps and summary go at once (none of them is this mission's plan
// until the answer comes), and stay gone if the planner fails.
async function runPlan() {
  $('messages').textContent = '';
  clearRun();
  state.route = new Set();
  draw();
  try {
    const t0 = performance.now();
    const result = await api.plan(state.map.id, state.mission, $('time-limit').value);
    state.timings.plan_round_trip_ms = Math.round(performance.now() - t0);
    state.planText = result.text;  // for the GeoJSON export
    state.route = new Set(result.steps.flatMap((s) => [s.pipe, s.from_pipe, s.to_pipe]).filter(Boolean));
    plans.planned(result);
    renderPlanRisk($('plan-risk'), result);
    state.planOrder = planOrder(result.steps);
    draw();
  } catch (e) {
    $('messages').textContent = e.message;
    plans.clear(`No plan: ${e.message}`);
    renderPlanRisk($('plan-risk'), null);
  }
}

// The open map's findings for the profile and risk mode (GET /findings), drawn with the legend;
// only the latest request's answer is used.
let findingsAsked = 0;
async function loadFindings() {
  if (!state.map) return;
  const asked = ++findingsAsked, map = state.map;
  try {
    const doc = await api.findings(map.id, $('profile').value);
    if (asked !== findingsAsked || state.map !== map) return;
    state.findings = placeFindings(map, doc);
    document.body.dataset.findings = `${map.id}:${doc.risk}:${doc.findings.length}`;
  } catch (e) {
    if (asked !== findingsAsked) return;
    state.findings = [];
    $('condition').textContent = `findings: ${e.message}`;
  }
  showLegend();
  draw();
}

function showLegend() {
  renderLegend($('overlay-legend'), { findings: state.findings, risk: api.settings.risk, learnt: state.learntDoc });
}

// What the robot learnt on the run (the `learnt` event), drawn and offered for download.
function showLearnt(doc) {
  state.learntDoc = doc;
  state.learnt = doc ? learntPlaces(state.map, doc) : [];
  const l = doc?.learnt, d = doc?.measurements;
  $('learnt-summary').textContent = doc
    ? `Learnt: ${l.blockages.length} blocked, ${l.danger.length} danger spots, ${l.closed_passages.length} passages closed; ` +
      `measured ${d.pipes_measured} pipes, ${d.discrepancies.length} map corrections` +
      (d.discrepancies.length ? ` (${d.discrepancies.map((x) => x.text).join('; ')})` : '')
    : '';
  $('learnt-json').disabled = $('learnt-geojson').disabled = !doc;
  $('learnt-downloads').hidden = !doc;  // in the results column only once there is something learnt
  showLegend();
  draw();
}

// The reader's warnings of the open map and its condition data's, each linked to its objects.
function showWarnings() {
  const info = state.mapInfo.get(state.map.id) ?? {};
  const warnings = [...info.warnings ?? [], ...info.condition_warnings ?? []];
  $('warnings-count').textContent = warnings.length ? `${warnings.length} warning${warnings.length === 1 ? '' : 's'} reading the map` : '';
  $('warnings').hidden = warnings.length === 0;
  renderWarnings($('warnings-list'), state.map, warnings, (objects) => {
    state.highlight = objects;
    draw();
    const points = [...objects.manholes.map((n) => state.map.manholeByName.get(n).position),
                    ...objects.pipes.map((n) => state.map.pipeByName.get(n)).filter((p) => !p.placeless).flatMap((p) => [p.from, p.to])];
    view.focus(points);
  });
}

// --- simulation and replay ---

function clearRun() {
  state.oldRoutes = [];
  state.failures = [];
  state.dropped = new Set();
  state.done = new Set();
  state.events = [];
  state.delays_ms = [];
  state.outcome = null;
  state.beacon = false;
  state.highlight = null;
  state.runMission = null;
  plans.clear();
  $('events').replaceChildren();
  $('outcome').textContent = '';
  showLearnt(null);
  player.reset(placePoint(state.map, state.mission?.start));
  view.drawRobot(null, false);
}

function logLine(type, text) {
  const li = document.createElement('li');
  li.className = type;
  li.textContent = text;
  $('events').append(li);
  li.scrollIntoView({ block: 'nearest' });
}

// A plan event's tasks: its goals and those it dropped; the final one named by its end.
function runTasks(e) {
  const final = /final task '([^']*)'/.exec(e.end ?? '')?.[1];
  return { tasks: [...new Set([...e.goals ?? [], ...e.dropped ?? []])].map((name) => ({ name, final: name === final })) };
}

const fmt = (t) => `${(t ?? 0).toFixed(1)} s`;

// One event, when the player reaches its time: the log, the map, the robot's motion.
function playEvent(type, e) {
  state.events.push({ type, ...e });
  const map = state.map;
  switch (type) {
    case 'route': {
      // The plan just announced: the route before it becomes an old route.
      if (state.events.filter((x) => x.type === 'route').length > 1 && state.route.size > 0) state.oldRoutes.push(state.route);
      state.route = new Set(e.pipes ?? pipesOfSteps(map, e.steps));
      plans.route(e, state.route);
      draw();
      return;
    }
    case 'plan': case 'replan':
      plans.event(type, e);
      // The run's tasks, from its first plan (a replayed log's mission is not the one edited).
      state.runMission ??= runTasks(e);
      logLine(type, `${fmt(e.t_s)} ${type}: ${e.reason} → ${e.decision}, ${e.steps} steps, ends ${e.end}` +
                    `${e.dropped.length ? `; drops ${e.dropped.join(', ')}` : ''}`);
      return;
    case 'action': {
      const to = actionTarget(map, e, state.mission);
      if (to) player.moveTo(to, e.t_s, e.duration_s);
      logLine(type, `${fmt(e.t_s)} ${e.step}`);
      return;
    }
    case 'error': {
      const at = wherePoint(map, e.where);
      if (at) player.placeAt(at, e.t_s);
      logLine(type, `${fmt(e.t_s)} error: ${e.kind}, ${e.reason} (${e.where})`);
      return;
    }
    case 'recovery':
      logLine(type, `${fmt(e.t_s)} recovery phase ${e.phase}: ${e.ok ? 'cleared' : 'failed'}`);
      return;
    case 'failure': {
      const at = e.pipe ? placePoint(map, { pipe: e.pipe, offset_m: e.offset_m }) : placePoint(map, { manhole: e.manhole });
      if (at) state.failures.push(at);
      logLine(type, `${fmt(e.t_s)} FAILURE ${e.kind}: ${e.detail}`);
      draw();
      return;
    }
    case 'task_done':
      state.done.add(e.task);
      logLine(type, `${fmt(e.t_s)} task ${e.task} done`);
      break;
    case 'task_dropped':
      state.dropped.add(e.task);
      plans.dropped(e.task, e.reason);
      logLine(type, `${fmt(e.t_s)} task ${e.task} DROPPED: ${e.reason}`);
      break;
    case 'beacon':
      state.beacon = true;
      logLine(type, `${fmt(e.t_s)} BEACON ON: ${e.reason}`);
      break;
    case 'mission_end':
      state.outcome = e;
      if (e.outcome === 'beacon') state.beacon = true;
      ({ text: $('outcome').textContent, className: $('outcome').className } =
        outcomeLine(e, state.runMission, state.dropped));
      logLine(type, `${fmt(e.t_s)} mission end: ${e.outcome}, ${e.end}; done: ${e.tasks_done.join(', ') || 'none'}; ` +
                    `${e.replans} replans, ${e.energy_wh.toFixed(1)} Wh`);
      break;
    case 'report':
      state.report = e;
      return;
    case 'learnt':
      showLearnt(e);
      return;
    default:
      return;
  }
  renderTasks($('tasks'), state.mission, missionChanged, taskStatus);
  draw();
}

const player = new Player({
  onEvent: (type, data) => playEvent(type, data),
  onRobot: (point) => { state.robot = point; view.drawRobot(point, state.beacon); },
});

let running = null;
async function runSimulation() {
  running?.abort();  // a new run cancels the last one's stream, and the server halts it
  running = new AbortController();
  clearRun();
  player.speed = Number($('speed').value);
  const body = { mission: state.mission };
  if ($('random-faults').value.trim()) body.random_faults = $('random-faults').value.trim();
  else if (!isEmpty(state.faults)) body.faults = state.faults;
  try {
    await api.simulate(state.map.id, body, (type, data, meta) => {
      if (meta.wall_ms !== null) state.delays_ms.push(meta.received_ms - meta.wall_ms);
      player.push(type, data, meta);
    }, running.signal);
  } catch (e) {
    if (e.name !== 'AbortError') $('messages').textContent = e.message;
  }
}

// Plays a log's events in the player, as a simulation's stream: each plan followed by its route,
// given ({"type": "route", "pipes"}, a campaign run's) or else the steps its actions ran until the
// next plan (a `simulate --log` file has no routes).
function playEvents(events) {
  running?.abort();  // a new run cancels the last one's stream, and the server halts it
  clearRun();
  player.speed = Number($('speed').value);
  const isPlan = (e) => e.type === 'plan' || e.type === 'replan';
  const hasRoutes = events.some((e) => e.type === 'route');
  let steps = [];
  for (const e of events) {
    if (e.type === 'route') {
      player.push('route', e);
    } else if (isPlan(e) && !hasRoutes) {
      player.push(e.type, e);
      steps = [];
      player.push('route', { steps });
    } else {
      if (e.type === 'action') steps.push(e.step);
      player.push(e.type, e);
    }
  }
}

// Replays a `simulate --log` file in the same player: the server reads it back (api replay).
async function replayLog(file) {
  try {
    const { events } = await api.replay(state.map.id, await file.text());
    playEvents(events);
  } catch (e) {
    $('messages').textContent = e.message;
  }
}

async function uploadMission(file) {
  try {
    const mission = JSON.parse(await file.text());
    if (mission.format !== 'sewerplan-mission') throw new Error(`${file.name}: not a sewerplan mission`);
    const known = [...$('profile').options].some((o) => o.value === mission.profile);
    if (mission.profile && !known) {
      throw new Error(`${file.name}: profile '${mission.profile}' is not one the station has (${[...$('profile').options].map((o) => o.value).join(', ')})`);
    }
    state.mission = mission;
    clearRun();
    state.route = new Set();
    // The profile selected and the map's driveability drawn for it, as a choice in the selector does.
    if (mission.profile && $('profile').value !== mission.profile) {
      $('profile').value = mission.profile;
      loadDriveability();
    }
    missionChanged();
  } catch (e) {
    $('messages').textContent = e.message;
  }
}

async function listMaps() {
  const { maps, profiles, basemap: source } = await api.listMaps();
  basemap ??= newBasemap(source);
  state.mapInfo = new Map(maps.map((m) => [m.id, m]));  // warnings, CRS ("EPSG:25832" or null)
  $('map').replaceChildren(...maps.map((m) => new Option(`${m.id} (${m.manholes} manholes)`, m.id)));
  return { maps, profiles };
}

// The basemap of the station's tile source (null: none), off until the operator turns it on.
function newBasemap(source) {
  const made = new Basemap({
    source, placement: api.basemap, tile: api.tile,
    onChange: () => { $('basemap-note').textContent = made.note; view.redraw(); },
  });
  $('basemap').disabled = !source;
  $('basemap').checked = false;
  $('basemap').onchange = () => { made.setEnabled($('basemap').checked); askBasemap(); };
  $('basemap-note').textContent = made.note;
  return made;
}

// A map file sent to the server (any format it reads), listed and opened under its new ID.
async function uploadMap(file) {
  try {
    const { id } = await api.uploadMap(file.name, await file.text());
    await listMaps();
    $('map').value = id;
    await openMap(id);
  } catch (e) {
    $('messages').textContent = e.message;
  }
}

// The open map's inspection findings (ISYBAU Zustandsdaten), joined to it on the server: what they
// close shows in the driveability, and campaigns can draw obstacles from them.
async function uploadCondition(file) {
  try {
    const r = await api.uploadCondition(state.map.id, file.name, await file.text());
    $('condition').textContent = `${r.findings} findings from ${r.condition}` +
      (r.warnings.length ? ` (${r.warnings.length} warnings, below)` : '');
    const info = state.mapInfo.get(state.map.id);
    if (info) info.condition_warnings = r.warnings;
    showWarnings();
    loadFindings();
    await loadDriveability();
  } catch (e) {
    $('condition').textContent = e.message;
  }
}

async function start() {
  const t0 = performance.now();
  const { maps, profiles } = await listMaps();
  $('profile').replaceChildren(...profiles.map((p) => new Option(p, p)));
  $('map-upload').onchange = (e) => e.target.files[0] && uploadMap(e.target.files[0]);
  $('condition-upload').onchange = (e) => e.target.files[0] && uploadCondition(e.target.files[0]);
  $('map').onchange = () => openMap($('map').value).catch((e) => { $('messages').textContent = e.message; });
  $('profile').onchange = () => { loadDriveability(); loadFindings(); missionChanged(); };
  $('motion').onchange = () => { api.settings.motion = $('motion').checked; loadDriveability(); };
  $('risk').onchange = () => { api.settings.risk = $('risk').value; loadFindings(); };
  $('learnt-json').onclick = () => download(`${state.map.id}-learnt.json`, state.learntDoc.learnt);
  $('learnt-geojson').onclick = () => download(`${state.map.id}-learnt.geojson`, learntGeoJson(state.learnt, state.map.id));
  $('plan').onclick = runPlan;
  $('simulate').onclick = runSimulation;
  $('speed').onchange = () => { player.speed = Number($('speed').value); };
  $('add-malfunction').onclick = () => {
    state.faults.malfunctions.push({ at_job: Number($('malfunction-job').value), kind: 'transient' });
    faultsChanged();
  };
  $('mission-download').onclick = () => download(`${state.mission.name}.json`, state.mission);
  $('mission-upload').onchange = (e) => e.target.files[0] && uploadMission(e.target.files[0]);
  $('replay-upload').onchange = (e) => e.target.files[0] && replayLog(e.target.files[0]);
  // GIS habits: search by name, fit, undo and redo, the editor's keys, the cursor's coordinates.
  $('search').onkeydown = (e) => { if (e.key === 'Enter') search(); };
  $('search').oninput = (e) => {
    if (!state.map) return;
    if (e.inputType === 'insertReplacementText' || e.inputType === undefined) search();  // a suggestion picked
    else $('search-names').replaceChildren(...suggestions(state.map, $('search').value).map((n) => new Option(n)));
  };
  $('fit').onclick = fitView;
  $('export-geojson').onclick = () => exportGeoJson(state).then((said) => { $('search-note').textContent = said; },
                                                            (e) => { $('search-note').textContent = e.message; });
  $('undo').onclick = undo;
  $('redo').onclick = redo;
  bindEditorKeys({ undo, redo, remove: removeSelected, fit: fitView });
  trackCursor($('view'), view, $('coords'), () => (state.map ? state.mapInfo.get(state.map.id)?.crs ?? null : null));
  campaign = new CampaignPanel($, {
    mapId: () => state.map.id,
    mission: () => state.mission,
    onOpenRun: (index, events) => { state.openedRun = index; playEvents(events); },
    onError: (message) => { $('campaign-status').textContent = message; },
  });
  if (maps.length > 0) await openMap(maps[0].id);
  else view.say('No map to open: upload one');
  state.timings.first_draw_ms = Math.round(performance.now() - t0);
  // Since navigation started: when the page's code started, and when the map was drawn.
  state.timings.started_at_ms = Math.round(t0);
  state.timings.ready_at_ms = Math.round(performance.now());
  document.body.dataset.ready = 'true';
}

let campaign = null;
state.timings = {};
start().catch(showFatal);

// For the browser test (e2e/): the state, the player, and where a pipe's point is on the screen.
window.station = {
  state,
  player,
  get campaign() { return campaign; },
  openMap,
  screenPoint(name, fraction) {
    const pipe = state.map.pipeByName.get(name);
    return view.project(placePoint(state.map, { pipe: name, offset_m: fraction * pipe.length_m }));
  },
  manholePoint(name) { return view.project(state.map.manholeByName.get(name).position); },
  // The map view: its view state, setView and drawing statistics (frames, LOD, picks).
  view,
  // The basemap: its tiles asked, fetched and drawn (basemap.js's stats).
  get basemap() { return basemap; },
  // Zooms in by `levels` about the view's centre; resolves when it is drawn.
  zoomAndWait(levels) {
    const { target, zoom } = view.viewState();
    view.setView({ target, zoom: zoom + levels });
    return afterDraw();
  },
};
