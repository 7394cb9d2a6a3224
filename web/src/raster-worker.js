// SPDX-License-Identifier: MIT
// The map view's rasterizer (lod.js), off the page's main thread: a window's image is drawn here
// while the page keeps moving the last one at every frame. Messages in: {map: columns} (a new map,
// workerColumns, its buffers transferred), {classes} (each pipe's class for a profile, a
// Uint8Array transferred), {id, key} (draw the window); out: {id, key, image, bounds, ms,
// recoloured}, the image transferred. The last window's layers are kept (WindowImage): the same
// key asked again after another profile's classes only recolours it.
import { GridIndex, WindowImage } from './lod.js';

let index = null;
let classes = null;
let last = null;  // the last window's WindowImage
self.onmessage = ({ data }) => {
  if (data.map) {
    index = new GridIndex(data.map);
    last?.close();
    last = null;
  }
  if (data.classes) classes = data.classes;
  if (!data.key || !index || !classes) return;
  const t0 = performance.now();
  const recoloured = last?.serves(data.key) ?? false;
  if (!recoloured) {
    last?.close();
    last = new WindowImage(index, data.key);
  }
  const image = last.compose(classes);
  self.postMessage({ id: data.id, key: data.key, image, bounds: last.bounds, recoloured,
                     ms: performance.now() - t0 }, [image]);
};
