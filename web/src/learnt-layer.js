// SPDX-License-Identifier: MIT
// What the robot learnt on a run (the simulation's `learnt` event, docs/operator-station.md): the
// blockages its recovery could not clear, the danger spots, the manhole passages it closed, and
// the map corrections its measurements show (discrepancies: a pipe's length or a manhole's place
// off, a junction the map lacks). Drawn over the network and exported: as the CLI's learnt JSON
// (`simulate --learnt FILE` reads it for the next mission) or as GeoJSON in the map's own
// coordinates.
import { LineLayer, ScatterplotLayer } from '@deck.gl/layers';
import { placePoint, pointOnPipe } from './geometry.js';

export const kLearntColours = {
  blockage: [20, 20, 20], danger: [255, 200, 0], passage: [200, 0, 200], correction: [0, 190, 210],
};

// The learnt document as places on the map: [{kind, at: [x, y] | line: [[x, y], [x, y]], text,
// properties}].
export function learntPlaces(map, doc) {
  const places = [];
  if (!doc) return places;
  const inPipe = (kind, list, what) => {
    for (const b of list ?? []) {
      const pipe = map.pipeByName.get(b.pipe);
      if (!pipe || pipe.placeless) continue;
      places.push({ kind, at: pointOnPipe(pipe, b.offset_m), text: `${what} in ${b.pipe} at ${b.offset_m.toFixed(2)} m`,
                    properties: { pipe: b.pipe, offset_m: b.offset_m } });
    }
  };
  inPipe('blockage', doc.learnt.blockages, 'blocked');
  inPipe('danger', doc.learnt.danger, 'danger spot');
  for (const p of doc.learnt.closed_passages ?? []) {
    const at = placePoint(map, { manhole: p.manhole });
    if (at) {
      places.push({ kind: 'passage', at, text: `passage ${p.manhole} ${p.from_slot} to ${p.to_slot} closed`,
                    properties: { manhole: p.manhole, from_slot: p.from_slot, to_slot: p.to_slot } });
    }
  }
  for (const d of doc.measurements?.discrepancies ?? []) {
    const pipe = d.pipe !== undefined ? map.pipeByName.get(d.pipe) : null;
    const properties = { discrepancy: d.kind, ...d };
    if (d.kind === 'unmapped-junction' && pipe && !pipe.placeless) {
      places.push({ kind: 'correction', at: pointOnPipe(pipe, d.offset_m), text: d.text, properties });
    } else if (pipe && !pipe.placeless) {
      places.push({ kind: 'correction', line: [pipe.from, pipe.to], text: d.text, properties });
    } else if (d.manhole !== undefined) {
      const at = placePoint(map, { manhole: d.manhole });
      if (at) places.push({ kind: 'correction', at, text: d.text, properties });
    }
  }
  return places;
}

export function learntLayers(places) {
  if (places.length === 0) return [];
  const points = places.filter((p) => p.at), lines = places.filter((p) => p.line);
  return [
    new LineLayer({
      id: 'learnt-lines', data: lines, getSourcePosition: (p) => p.line[0], getTargetPosition: (p) => p.line[1],
      getColor: kLearntColours.correction, getWidth: 5, widthUnits: 'pixels',
    }),
    new ScatterplotLayer({
      id: 'learnt', data: points, getPosition: (p) => p.at, radiusUnits: 'pixels',
      getRadius: (p) => (p.kind === 'passage' ? 13 : 8),
      filled: true, getFillColor: (p) => (p.kind === 'passage' ? [0, 0, 0, 0] : kLearntColours[p.kind]),
      stroked: true, lineWidthUnits: 'pixels', getLineWidth: (p) => (p.kind === 'passage' ? 4 : 2),
      getLineColor: (p) => (p.kind === 'passage' ? kLearntColours.passage : p.kind === 'blockage' ? [220, 0, 0] : [255, 255, 255]),
    }),
  ];
}

// GeoJSON of the places, in the map's own coordinates (metres of its CRS; not WGS84: the page has
// no projection; `sewerplan export-geojson` reprojects a map's layers).
export function learntGeoJson(places, mapId) {
  return {
    type: 'FeatureCollection',
    name: `${mapId}-learnt`,
    sewerplan: { map: mapId, coordinates: "the map's own (its CRS's metres), not WGS84" },
    features: places.map((p) => ({
      type: 'Feature',
      geometry: p.at ? { type: 'Point', coordinates: p.at } : { type: 'LineString', coordinates: p.line },
      properties: { learnt: p.kind, text: p.text, ...p.properties },
    })),
  };
}
