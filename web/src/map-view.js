// SPDX-License-Identifier: MIT
// The map view: deck.gl in an OrthographicView (WebGL, the network's own metres, no tiles). The
// network is drawn at a level of detail (lod.js): the pipes and manholes of a window around the
// view, as a LineLayer and a ScatterplotLayer of binary columns when they are few, else as an
// image of the window drawn by a worker (raster-worker.js) and shown in a 2-D canvas under deck.gl's,
// moved and scaled with the view at each frame; either is rebuilt only when the view leaves the
// window or the zoom level changes. Hover and click pick on the CPU from lod.js's grid (no GPU
// picking pass, which would draw the scene again). The routes, the mission, the hidden faults
// and the robot are small deck.gl layers over it.
import { OrthographicView } from '@deck.gl/core';
import { LineLayer, ScatterplotLayer, TextLayer } from '@deck.gl/layers';
import { placePoint, pointOnPipe } from './geometry.js';
import { labelWidth, thinLabels } from './labels.js';
import { GridIndex, keyServes, lodKey, mapColumns, pick, pipeClasses, vectorData, workerColumns } from './lod.js';
import { NetworkPicture } from './network-picture.js';
import { findingsLayer } from './findings-layer.js';
import { learntLayers } from './learnt-layer.js';
import { taskLayers } from './task-markers.js';
import { FirstView, LaterDeck } from './first-view.js';

const kNamesUpTo = 2000;  // manhole names (thinned: labels.js) only on maps this small

// scene: {map, blocked: Map(pipe -> reason), route: Set, oldRoutes: [Set], mission, faults,
//         failures: [[x, y]], robot: [x, y] | null, beacon: bool, findings: [placed finding],
//         learnt: [learnt place], planOrder: Map(task -> number),
//         highlight: {pipes: [name], manholes: [name]} | null (a warning's objects, a plan chosen,
//         a place found by name: highlightLayers)}
// onViewChange(viewState) after every pan and zoom (the scale bar, the basemap).
// underlay(g, toScreen) draws under the network on the 2-D canvas, at each frame (the basemap,
// basemap.js): g's transform the identity, toScreen([x, y]) the map's metres in its pixels.
export function createMapView(parent, { onClick, onHover, onViewChange = () => {}, underlay = () => {} }) {
  let viewState = { target: [0, 0, 0], zoom: 0 };
  let hovering = false;
  // What the browser test reads (web/e2e): frames drawn, LOD rebuilds and picks, timed; the
  // main thread's part of each image shown (images: from its message to its first blit).
  const stats = { renders: 0, lod: [], picks: [], images: [] };
  const drawn = [];  // resolves of whenDrawn()
  // The window's image, under deck.gl's canvas (which is transparent where nothing is drawn), in
  // device pixels, as deck.gl's.
  const under = document.createElement('canvas');
  Object.assign(under.style, { position: 'absolute', left: '0', top: '0', width: '100%', height: '100%' });
  parent.prepend(under);
  // A new map's first picture (canvas 2D) and the loading note, while deck.gl's shaders compile.
  const first = new FirstView(parent, under);
  stats.firstView = first.stats;
  const deck = new LaterDeck({  // made once a map's first picture is on screen (first-view.js)
    parent,
    views: new OrthographicView({ flipY: false }),
    controller: { doubleClickZoom: false },  // clicks place tasks: none may zoom
    // deck.gl holds every click back for the double-click interval (300 ms), in case a second
    // follows; with no double-click zoom none is wanted, so a click places its task at once.
    eventRecognizerOptions: { click: { interval: 0 } },
    initialViewState: viewState,
    onViewStateChange: ({ viewState: v }) => { viewState = v; viewChanged(); refresh(); },
    getCursor: ({ isDragging }) => (isDragging ? 'grabbing' : hovering ? 'pointer' : 'grab'),
    onHover: (info, event) => {
      const t0 = performance.now();
      const picked = pickAt(info);
      hovering = Boolean(picked.object);
      onHover(picked);
      const t1 = performance.now();
      // From the pointer's event to the hover shown, and the pick itself.
      stats.picks.push({ pick_ms: t1 - t0, event_to_shown_ms: t1 - (event?.srcEvent?.timeStamp ?? t0) });
    },
    onClick: (info) => onClick(pickAt(info)),
    onBeforeRender: () => { blit(); first.follow(viewState); },
    onAfterRender: () => {
      ++stats.renders;
      if (first.afterRender(deck.layers())) queueMicrotask(() => setLayers());  // without the warm-up
      if (!waiting && !first.holding) drawn.splice(0).forEach((resolve) => resolve());
    },
    layers: [],
  });
  let map = null;
  let index = null;    // the map's grid (lod.js)
  let classes = null;  // each pipe's class for the scene's profile
  let key = null;      // the window and level drawn
  const picture = new NetworkPicture();  // a 'vector' key's layers or the last image of a window
  let overlay = [];    // the routes, then the marks: change with the mission, the faults or a plan
  let drawnBlocked = null;
  let robotLayers = [];
  let labelLayer = null, labelZoom = null;  // the thinned names and the zoom they were thinned at
  const measure = labelWidth();

  // The worker draws one window at a time; a request made while it draws waits, and only the
  // latest waits (the view moved on).
  const worker = new Worker(new URL('./raster-worker.js', import.meta.url), { type: 'module' });
  let busy = false, next = null, waiting = false, requestId = 0;
  worker.onmessage = ({ data }) => {
    busy = false;
    if (data.id === requestId && key?.mode !== 'vector') {
      const hadLayers = picture.layers.length > 0;  // a 'vector' key's stay until the image replaces them
      picture.showImage(data);
      data.arrived = performance.now();
      stats.lod.push({ ms: data.ms, mode: data.key.mode, level: data.key.level,
                       drawn: `${data.recoloured ? 'recoloured' : 'an image of'} ${data.image.width}x${data.image.height}` });
      if (hadLayers) setLayers();
    } else {
      data.image.close();
    }
    if (next) request(next);
    else waiting = false;
    deck.redraw(true);
  };
  worker.onerror = (e) => {  // no image will come: say why, and let whenDrawn() resolve
    console.error(`the map's rasterizer failed: ${e.message}`);
    busy = waiting = false;
  };
  function request(k) {
    waiting = true;
    if (busy) { next = k; return; }
    busy = true;
    next = null;
    worker.postMessage({ id: ++requestId, key: k });
  }

  // Bottom to top: pipes, routes, manholes, then the mission's marks and the robot.
  const setLayers = () => {
    const network = picture.layers;
    deck.setProps({ layers: first.layers([network[0], overlay[0], network[1], ...overlay.slice(1), labelLayer, ...robotLayers].filter(Boolean),
                                         viewState.target) });
  };

  // The manholes' names, thinned so that none overlaps another (labels.js) at the zoom rounded
  // down to a quarter level: valid for every zoom above it, so thinned again only when the zoom
  // leaves that quarter. Returns whether the layer changed.
  function updateLabels() {
    const z = map && map.manholeCount <= kNamesUpTo ? Math.floor(viewState.zoom * 4) / 4 : null;
    if (z === labelZoom) return false;
    labelZoom = z;
    labelLayer = z === null ? null : new TextLayer({
      id: 'names', data: thinLabels(map.manholes, z, measure), getPosition: (m) => m.position,
      getText: (m) => m.name, getSize: 11, getPixelOffset: [0, -12], characterSet: 'auto', fontFamily: 'monospace',
    });
    return true;
  }

  function viewChanged() {
    if (updateLabels()) setLayers();
    onViewChange(viewState);
  }

  // The view's rectangle in metres (2^zoom CSS pixels a metre) and the screen's pixel ratio.
  function viewOf(v) {
    const half = 2 ** -v.zoom / 2, w = parent.clientWidth * half, h = parent.clientHeight * half;
    return { zoom: v.zoom, rect: [v.target[0] - w, v.target[1] - h, v.target[0] + w, v.target[1] + h],
             dpr: devicePixelRatio };
  }

  // Shows the window's image where the view has it (each frame: a 2-D canvas blit, milliseconds),
  // over the underlay (the basemap). A new image replaces the last in one blit: the last stays
  // shown, scaled, until it comes. None is shown while a vector window's layers are
  // (NetworkPicture).
  function blit() {
    const dpr = devicePixelRatio;
    const width = Math.round(parent.clientWidth * dpr), height = Math.round(parent.clientHeight * dpr);
    if (under.width !== width || under.height !== height) Object.assign(under, { width, height });
    const g = under.getContext('2d');
    g.clearRect(0, 0, width, height);
    const { rect, zoom } = viewOf(viewState), s = 2 ** zoom * dpr;
    underlay(g, (p) => [(p[0] - rect[0]) * s, (rect[3] - p[1]) * s]);
    const image = picture.image;
    if (!image) return;
    const [x0, y0, x1, y1] = image.bounds;
    const t0 = performance.now();
    g.drawImage(image.image, (x0 - rect[0]) * s, (rect[3] - y1) * s, (x1 - x0) * s, (y1 - y0) * s);
    if (image.arrived !== undefined) {
      stats.images.push({ first_blit_ms: performance.now() - t0, message_to_blit_ms: performance.now() - image.arrived });
      delete image.arrived;
    }
  }

  // Rebuilds the network's layers, or asks for the window's image, when the view left the window
  // drawn or changed its level.
  function refresh() {
    if (!index) return;
    const view = viewOf(viewState);
    if (keyServes(key, view)) return;
    key = lodKey(index, view);
    if (key.mode !== 'vector') {
      request(key);
      return;
    }
    const t0 = performance.now();
    const data = vectorData(index, key, classes);
    picture.showLayers([
      new LineLayer({ id: 'pipes', data: data.pipes, widthUnits: 'pixels' }),
      new ScatterplotLayer({ id: 'manholes', data: data.manholes, radiusUnits: 'pixels' }),
    ]);
    stats.lod.push({ ms: performance.now() - t0, mode: key.mode, level: key.level,
                     drawn: `${data.pipes.length} lines, ${data.manholes.length} circles` });
    setLayers();
  }

  // The feature under the pointer as deck.gl's picking info reads ({layer: {id}, object}).
  function pickAt(info) {
    if (!index || !key || !info.coordinate) return info;
    const hit = pick(index, key.mode === 'overview', info.coordinate, viewState.zoom);
    if (!hit) return { ...info, layer: null, object: null };
    const pipe = hit.kind === 'pipe';
    return { ...info, layer: { id: pipe ? 'pipes' : 'manholes' }, object: pipe ? map.pipe(hit.index) : map.manhole(hit.index) };
  }

  function overlayLayers(s) {
    const map = s.map;
    const old = new Set(s.oldRoutes.flatMap((r) => [...r]));
    const routed = [...new Set([...old, ...s.route])].map((n) => map.pipeByName.get(n)).filter(Boolean);
    const layers = [
      new LineLayer({
        id: 'routes', data: routed,
        getSourcePosition: (p) => p.from, getTargetPosition: (p) => p.to,
        getColor: (p) => (s.route.has(p.name) ? [230, 120, 0] : [150, 110, 200]),
        getWidth: (p) => (s.route.has(p.name) ? 6 : 4), widthUnits: 'pixels',
      }),
    ];
    // The findings under the mission's marks, what the robot learnt over them (findings-layer.js,
    // learnt-layer.js, task-markers.js).
    if (s.findings?.length) layers.push(findingsLayer(s.findings));
    layers.push(...learntLayers(s.learnt ?? []), ...taskLayers(map, s));
    const faults = faultPoints(map, s.faults);
    layers.push(new ScatterplotLayer({
      id: 'faults', data: faults, getPosition: (f) => f.at, radiusUnits: 'pixels', getRadius: 6,
      getFillColor: (f) => (f.kind === 'permanent' ? [120, 0, 0] : f.kind === 'danger' ? [255, 90, 0] : [200, 120, 120]),
      stroked: true, getLineColor: [255, 255, 255], lineWidthUnits: 'pixels', getLineWidth: 2,
    }));
    // Every layer gets an array of its own, made here: deck.gl redraws a layer only when its data is
    // another array than last time, so an array of the page's state, changed in place (a failure
    // pushed while the run plays), would never be drawn again (the failure ring at paced speeds).
    layers.push(new ScatterplotLayer({
      id: 'failures', data: [...s.failures], getPosition: (f) => f, radiusUnits: 'pixels', getRadius: 10,
      filled: false, stroked: true, getLineColor: [220, 0, 0], lineWidthUnits: 'pixels', getLineWidth: 3,
    }));
    layers.push(...highlightLayers(map, s.highlight));
    return layers;
  }

  const setView = (v, { now = true } = {}) => {
    viewState = { target: [v.target[0], v.target[1], 0], zoom: v.zoom };
    deck.setProps({ initialViewState: viewState });
    if (map) viewChanged();
    if (now) refresh();
  };

  return {
    deck,
    stats,
    // Draws a changed scene (map, profile, mission, plan or fault); the network's layers are
    // rebuilt only for another map or profile.
    draw(s) {
      if (!s.map) return;
      const fresh = s.map !== map;
      if (fresh) {
        map = s.map;
        index = null;  // made once the first picture is on screen (below)
        picture.clear();
        ++requestId;  // an image of the last map still being drawn is not shown
        key = null;
        drawnBlocked = null;
        labelZoom = undefined;  // the names are thinned again for this map
      }
      if (s.blocked !== drawnBlocked) {
        classes = pipeClasses(map, s.blocked);
        const copy = classes.slice();
        worker.postMessage({ classes: copy }, [copy.buffer]);
        drawnBlocked = s.blocked;
        // An image's window is asked again: the worker recolours the one it has. A vector
        // window's layers are rebuilt (a few hundred pipes).
        if (key?.mode === 'vector') key = null;
        else if (key) request(key);
      }
      // A new map's picture at once (the view is fitted to it); its grid, the worker's columns and
      // the layers once it is on screen: they held a 100,000-manhole map's picture back 0.6 s.
      if (fresh) {
        first.start(mapColumns(map), classes, viewState, () => {
          index = new GridIndex(mapColumns(map));
          const { columns, transfer } = workerColumns(map);
          worker.postMessage({ map: columns }, transfer);  // the classes were sent before: the worker keeps them
          deck.make();
          refresh();
          setLayers();
          deck.redraw(true);
        });
      }
      overlay = overlayLayers(s);
      updateLabels();
      if (!key) refresh();
      setLayers();
    },
    // What the map's first view said (first-view.js), for a page with no map to open.
    say: (text) => { first.say(text); deck.make(); },
    // Moves the robot only: one small layer per animation frame.
    drawRobot(robot, beacon) {
      robotLayers = robot ? [new ScatterplotLayer({
        id: 'robot', data: [robot], getPosition: (r) => r, radiusUnits: 'pixels',
        getRadius: beacon ? 14 : 9, getFillColor: beacon ? [255, 0, 0] : [220, 0, 120],
        stroked: beacon, getLineColor: [255, 230, 0], lineWidthUnits: 'pixels', getLineWidth: 4,
        updateTriggers: { getRadius: beacon, getFillColor: beacon },
      })] : [];
      setLayers();
    },
    // Fits the view to a new map's bounds; its network is drawn by the next draw() (with the
    // map's grid: the last map's would be drawn in vain).
    // now: drawn at once (the Fit button), not by the next draw().
    fit([x0, y0, x1, y1], { now = false } = {}) {
      const size = Math.max(x1 - x0, y1 - y0, 1);
      const zoom = Math.log2(Math.min(parent.clientWidth, parent.clientHeight) / (size * 1.1));
      setView({ target: [(x0 + x1) / 2, (y0 + y1) / 2], zoom }, { now });
    },
    // Shows `points` ([x, y] in metres): the view centred on them, zoomed to hold them all with a
    // margin (at least 40 m across), never further out than the whole map.
    focus(points) {
      if (points.length === 0) return;
      const xs = points.map((p) => p[0]), ys = points.map((p) => p[1]);
      const [x0, y0, x1, y1] = [Math.min(...xs), Math.min(...ys), Math.max(...xs), Math.max(...ys)];
      const size = Math.max(x1 - x0, y1 - y0, 40) * 1.4;
      const zoom = Math.log2(Math.min(parent.clientWidth, parent.clientHeight) / size);
      setView({ target: [(x0 + x1) / 2, (y0 + y1) / 2], zoom });
    },
    // The view ({target, zoom}) and setting it, as a pan or a zoom would.
    viewState: () => viewState,
    // The view's rectangle in metres: [x0, y0, x1, y1].
    rect: () => viewOf(viewState).rect,
    // Draws the next frame (the underlay changed).
    redraw: () => deck.redraw(true),
    setView,
    // The manholes whose names are drawn (thinned: labels.js), and the zoom they were thinned at.
    labels: () => ({ zoom: labelZoom, manholes: labelLayer?.props.data ?? [] }),
    // Resolves when deck.gl has drawn the current layers and the window's image has come.
    whenDrawn() {
      const done = new Promise((resolve) => drawn.push(resolve));
      deck.redraw(true);
      return done;
    },
    // Where a map point is on the screen, in the view's pixels.
    project(point) {
      if (deck.made) return deck.getViewports()[0].project(point);
      const s = 2 ** viewState.zoom;  // before the Deck: its OrthographicView's projection (y up)
      return [(point[0] - viewState.target[0]) * s + parent.clientWidth / 2,
              (viewState.target[1] - point[1]) * s + parent.clientHeight / 2];
    },
  };
}

// What the page points the operator at (a warning's objects, a plan chosen in the Plan panel):
// {pipes: [name], manholes: [name]} drawn in cyan over everything but the robot.
function highlightLayers(map, highlight) {
  if (!highlight) return [];
  const pipes = (highlight.pipes ?? []).map((n) => map.pipeByName.get(n)).filter((p) => p && !p.placeless);
  const manholes = (highlight.manholes ?? []).map((n) => map.manholeByName.get(n)).filter(Boolean);
  return [
    new LineLayer({ id: 'highlight-pipes', data: pipes, getSourcePosition: (p) => p.from, getTargetPosition: (p) => p.to,
                    getColor: [0, 200, 230, 200], getWidth: 10, widthUnits: 'pixels' }),
    new ScatterplotLayer({ id: 'highlight-manholes', data: manholes, getPosition: (m) => m.position,
                           radiusUnits: 'pixels', getRadius: 12, filled: false, stroked: true,
                           getLineColor: [0, 200, 230], lineWidthUnits: 'pixels', getLineWidth: 4 }),
  ];
}

// The hidden faults (a fault scenario, docs/simulation.md) as points: obstacles and danger spots
// at their offsets, dangerous passages at their manholes.
function faultPoints(map, faults) {
  const points = [];
  for (const o of faults.obstacles ?? []) {
    const pipe = map.pipeByName.get(o.pipe);
    if (pipe) points.push({ kind: o.kind, at: pointOnPipe(pipe, o.offset_m) });
  }
  for (const d of faults.danger ?? []) {
    const at = placePoint(map, d);
    if (at) points.push({ kind: 'danger', at });
  }
  return points;
}
