// SPDX-License-Identifier: MIT
// What the map view shows of the network (lod.js): one picture at a time, either a 'vector'
// window's deck.gl layers or the worker's image of a 'detail' or 'overview' window, never both.
// Entering a vector window drops the last image (it may be of another window or level, and holds
// up to 48 MB); leaving one keeps its layers shown until the next image replaces them, so the view
// never shows the layers over an older image of another level while that image is being drawn.
export class NetworkPicture {
  #layers = [];
  #image = null;  // {image: ImageBitmap, bounds, key, ...} as the worker posts it

  // The vector layers shown ([] while an image is).
  get layers() { return this.#layers; }

  // The image shown (null while vector layers are).
  get image() { return this.#image; }

  // Shows a vector window's layers instead of whatever was shown.
  showLayers(layers) {
    this.#dropImage();
    this.#layers = layers;
  }

  // Shows a window's image instead of whatever was shown.
  showImage(image) {
    this.#dropImage();
    this.#image = image;
    this.#layers = [];
  }

  // Shows nothing (another map).
  clear() {
    this.#dropImage();
    this.#layers = [];
  }

  #dropImage() {
    this.#image?.image.close();
    this.#image = null;
  }
}
