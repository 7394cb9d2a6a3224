// SPDX-License-Identifier: MIT
// The map view: deck.gl in an OrthographicView (WebGL, the network's own metres, no tiles). Pipes
// are one LineLayer and manholes one ScatterplotLayer, each one GPU draw call whatever the count;
// the mission, the hidden faults, the routes and the robot are small layers over them.
import { Deck, OrthographicView } from '@deck.gl/core';
import { LineLayer, ScatterplotLayer, TextLayer } from '@deck.gl/layers';
import { placePoint, pointOnPipe } from './geometry.js';

const kNamesUpTo = 2000;  // manhole names at every zoom only on maps this small

// scene: {map, blocked: Map(pipe -> reason), route: Set, oldRoutes: [Set], mission, faults,
//         failures: [[x, y]], robot: [x, y] | null, beacon: bool}
export function createMapView(parent, { onClick, onHover }) {
  const deck = new Deck({
    parent,
    views: new OrthographicView({ flipY: false }),
    controller: { doubleClickZoom: false },  // clicks place tasks: none may zoom
    // deck.gl holds every click back for the double-click interval (300 ms), in case a second
    // follows; with no double-click zoom none is wanted, so a click places its task at once.
    eventRecognizerOptions: { click: { interval: 0 } },
    initialViewState: { target: [0, 0, 0], zoom: 0 },
    getCursor: ({ isHovering }) => (isHovering ? 'pointer' : 'grab'),
    onHover,
    onClick,
    layers: [],
  });
  let base = [];  // the layers that change only with the map, the profile, the mission or a plan
  let robotLayers = [];

  function baseLayers(s) {
    const map = s.map;
    const old = new Set(s.oldRoutes.flatMap((r) => [...r]));
    const layers = [
      new LineLayer({
        id: 'pipes', data: map.pipes, pickable: true,
        getSourcePosition: (p) => p.from, getTargetPosition: (p) => p.to,
        getColor: (p) => (s.route.has(p.name) ? [230, 120, 0] : old.has(p.name) ? [150, 110, 200]
                          : s.blocked.has(p.name) ? [200, 40, 40] : p.openEnd ? [140, 140, 140] : [60, 90, 160]),
        getWidth: (p) => (s.route.has(p.name) ? 6 : old.has(p.name) ? 4 : 1 + 4 * Math.min(p.diameter_m, 1)),
        widthUnits: 'pixels',
        updateTriggers: { getColor: [s.route, s.blocked, s.oldRoutes], getWidth: [s.route, s.oldRoutes] },
      }),
      new ScatterplotLayer({
        id: 'manholes', data: map.manholes, pickable: true,
        getPosition: (m) => m.position, radiusUnits: 'pixels',
        getRadius: (m) => (m.exit ? 6 : 3 + Math.min(m.slots, 4) * 0.5),
        getFillColor: (m) => (m.exit ? [20, 150, 60] : [90, 90, 90]),
      }),
    ];
    const tasks = s.mission.tasks.map((t) => ({ t, at: placePoint(map, t.at ?? { pipe: t.pipe }) }))
      .filter((x) => x.at);
    const start = placePoint(map, s.mission.start);
    layers.push(new ScatterplotLayer({
      id: 'tasks', data: [...tasks, ...(start ? [{ t: { type: 'start' }, at: start }] : [])],
      getPosition: (x) => x.at, radiusUnits: 'pixels', getRadius: 7, stroked: true,
      getFillColor: (x) => (s.dropped.has(x.t.name) ? [170, 170, 170] : s.done.has(x.t.name) ? [60, 190, 90]
                            : x.t.type === 'start' ? [255, 255, 255] : [240, 200, 0]),
      getLineColor: [0, 0, 0], lineWidthUnits: 'pixels', getLineWidth: 1,
      updateTriggers: { getFillColor: [s.dropped.size, s.done.size] },
    }));
    const faults = faultPoints(map, s.faults);
    layers.push(new ScatterplotLayer({
      id: 'faults', data: faults, getPosition: (f) => f.at, radiusUnits: 'pixels', getRadius: 6,
      getFillColor: (f) => (f.kind === 'permanent' ? [120, 0, 0] : f.kind === 'danger' ? [255, 90, 0] : [200, 120, 120]),
      stroked: true, getLineColor: [255, 255, 255], lineWidthUnits: 'pixels', getLineWidth: 2,
    }));
    layers.push(new ScatterplotLayer({
      id: 'failures', data: s.failures, getPosition: (f) => f, radiusUnits: 'pixels', getRadius: 10,
      filled: false, stroked: true, getLineColor: [220, 0, 0], lineWidthUnits: 'pixels', getLineWidth: 3,
    }));
    if (map.manholes.length <= kNamesUpTo) {
      layers.push(new TextLayer({ id: 'names', data: map.manholes, getPosition: (m) => m.position,
                                  getText: (m) => m.name, getSize: 11, getPixelOffset: [0, -12],
                                  characterSet: 'auto', fontFamily: 'monospace' }));
    }
    return layers;
  }

  return {
    deck,
    // Redraws everything (a changed map, mission, plan or fault).
    draw(scene) {
      if (!scene.map) return;
      base = baseLayers(scene);
      deck.setProps({ layers: [...base, ...robotLayers] });
    },
    // Moves the robot only: one small layer per animation frame.
    drawRobot(robot, beacon) {
      robotLayers = robot ? [new ScatterplotLayer({
        id: 'robot', data: [robot], getPosition: (r) => r, radiusUnits: 'pixels',
        getRadius: beacon ? 14 : 9, getFillColor: beacon ? [255, 0, 0] : [220, 0, 120],
        stroked: beacon, getLineColor: [255, 230, 0], lineWidthUnits: 'pixels', getLineWidth: 4,
        updateTriggers: { getRadius: beacon, getFillColor: beacon },
      })] : [];
      deck.setProps({ layers: [...base, ...robotLayers] });
    },
    fit([x0, y0, x1, y1]) {
      const size = Math.max(x1 - x0, y1 - y0, 1);
      const zoom = Math.log2(Math.min(parent.clientWidth, parent.clientHeight) / (size * 1.1));
      deck.setProps({ initialViewState: { target: [(x0 + x1) / 2, (y0 + y1) / 2, 0], zoom } });
    },
    // Where a map point is on the screen, in the view's pixels.
    project(point) { return deck.getViewports()[0].project(point); },
  };
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
