// SPDX-License-Identifier: MIT
// The map view's rasterizer (lod.js), off the page's main thread: a window's image is drawn here
// while the page keeps moving the last one at every frame. Messages in: {map: columns} (a new map,
// mapColumns), {classes} (each pipe's class, for a profile), {id, key} (draw the window);
// out: {id, key, image, bounds, ms}, the image transferred.
import { GridIndex, rasterize } from './lod.js';

let index = null;
let classes = null;
self.onmessage = ({ data }) => {
  if (data.map) index = new GridIndex(data.map);
  if (data.classes) classes = data.classes;
  if (!data.key || !index || !classes) return;
  const t0 = performance.now();
  const { image, bounds } = rasterize(index, data.key, classes);
  self.postMessage({ id: data.id, key: data.key, image, bounds, ms: performance.now() - t0 }, [image]);
};
