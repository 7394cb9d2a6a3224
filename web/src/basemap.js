// SPDX-License-Identifier: MIT
// The optional basemap (docs/operator-station.md, "The basemap"): the tiles of the source that
// `serve --tiles` names, under the network, off until the operator turns it on. The map is drawn
// in its own metres (its CRS) and the tiles are Web Mercator: the server chooses the tiles that
// cover the view and places each tile's four corners in the map's metres, through PROJ
// (GET /api/maps/ID/basemap, server/basemap.h). This module asks for them as the view moves (one
// request at a time, the latest view next), fetches each tile once (a local directory's through
// the station's API, with the token; a URL's from its own server, never with the token), and draws
// them on the map view's 2-D canvas under the network (map-view.js's underlay): each tile as two
// triangles, each with the affine transform that puts its three corners where the server placed
// them, so all four corners are exact. Nothing is asked or fetched while it is off, for a map
// without a CRS, or with no source; the note says why nothing is drawn.
//
//   const basemap = new Basemap({ source, placement: api.basemap, tile: api.tile, onChange });
//   basemap.setMap(id, crs); basemap.setEnabled(true); basemap.view(rect, metresPerPixel);
//   basemap.draw(g, toScreen);   // in the map view's frame, before the network

const kCachedTiles = 256;  // images kept (ImageBitmaps, 256 kB each decoded)

// The two affine transforms (canvas setTransform's a, b, c, d, e, f) that map a w x h image onto
// `q`, its corners on the screen (top left, top right, bottom right, bottom left): the first
// exact on the top left, top right and bottom right corners, the second on the top left, bottom
// right and bottom left. For a parallelogram both are the same.
export function tileTransforms(q, w, h) {
  const [q0, q1, q2, q3] = q;
  const upper = [(q1[0] - q0[0]) / w, (q1[1] - q0[1]) / w, (q2[0] - q1[0]) / h, (q2[1] - q1[1]) / h, q0[0], q0[1]];
  const lower = [(q2[0] - q3[0]) / w, (q2[1] - q3[1]) / w, (q3[0] - q0[0]) / h, (q3[1] - q0[1]) / h, q0[0], q0[1]];
  return { upper, lower };
}

// What the page says of the basemap: nothing when it draws (or is off), else why it does not.
export function basemapNote({ source, enabled, crs, error }) {
  if (!source) return 'No basemap: start sewerplan serve with --tiles URL or DIR';
  if (!enabled) return '';
  if (!crs) return 'No basemap for this map: it names no coordinate reference system (local coordinates)';
  return error ?? '';
}

export class Basemap {
  #source;
  #placement;  // (mapId, rect, mpp) => Promise of the server's {tiles, note}
  #tile;       // (url, kind) => Promise of an ImageBitmap
  #onChange;
  #map = null;  // {id, crs}
  #enabled = false;
  #tiles = [];  // the placement drawn: [{url, corners}]
  #images = new Map();  // url -> {image: ImageBitmap | null, failed: string | null}
  #asking = false;
  #next = null;  // the latest view asked while a request runs
  #error = null;
  // What the browser test reads: placements asked, tile URLs fetched, tiles drawn in the last frame.
  stats = { placements: 0, fetched: [], failed: [], drawn: 0 };

  constructor({ source, placement, tile, onChange }) {
    this.#source = source;
    this.#placement = placement;
    this.#tile = tile;
    this.#onChange = onChange;
  }

  get enabled() { return this.#enabled; }
  get note() {
    return basemapNote({ source: this.#source, enabled: this.#enabled, crs: this.#map?.crs, error: this.#error });
  }

  // Another map is open: its CRS (null: local coordinates) says whether it can have a basemap.
  setMap(id, crs) {
    this.#map = { id, crs };
    this.#tiles = [];
    this.#next = null;
    this.#error = null;
    this.#onChange();
  }

  setEnabled(on) {
    this.#enabled = on;
    if (!on) { this.#tiles = []; this.#next = null; this.#error = null; }
    this.#onChange();
  }

  // The view moved: its rectangle in the map's metres and the metres a CSS pixel is.
  view(rect, metresPerPixel) {
    if (!this.#enabled || !this.#source || !this.#map?.crs) return;
    this.#next = { id: this.#map.id, rect, mpp: metresPerPixel };
    if (!this.#asking) this.#ask();
  }

  async #ask() {
    const asked = this.#next;
    this.#next = null;
    this.#asking = true;
    ++this.stats.placements;
    try {
      const placed = await this.#placement(asked.id, asked.rect, asked.mpp);
      if (this.#enabled && this.#map?.id === asked.id) {
        this.#tiles = placed.tiles;
        this.#error = placed.note ? `Basemap: ${placed.note}` : null;
        placed.tiles.forEach((t) => this.#fetch(t.url));
        this.#onChange();
      }
    } catch (e) {
      if (this.#map?.id === asked.id) { this.#error = `No basemap: ${e.message}`; this.#onChange(); }
    } finally {
      this.#asking = false;
      if (this.#next) this.#ask();
    }
  }

  #fetch(url) {
    if (this.#images.has(url)) return;
    const entry = { image: null, failed: null };
    this.#images.set(url, entry);
    this.stats.fetched.push(url);
    this.#tile(url, this.#source.kind).then((image) => { entry.image = image; this.#onChange(); }, (e) => {
      entry.failed = e.message;
      this.stats.failed.push(url);
      this.#error = `Basemap: ${this.stats.failed.length} tiles could not be fetched (${url}: ${e.message})`;
      this.#onChange();
    });
    // The oldest images go past the cache's size (a Map keeps the order of insertion).
    for (const [old, e] of this.#images) {
      if (this.#images.size <= kCachedTiles) break;
      e.image?.close();
      this.#images.delete(old);
    }
  }

  // Draws the placed tiles that have come on `g` (a 2-D context, its transform the identity),
  // `toScreen` mapping the map's metres to its pixels.
  draw(g, toScreen) {
    let drawn = 0;
    if (this.#enabled) {
      for (const t of this.#tiles) {
        const image = this.#images.get(t.url)?.image;
        if (!image) continue;
        const q = t.corners.map(toScreen);
        const { upper, lower } = tileTransforms(q, image.width, image.height);
        g.save();
        // The whole tile with the upper triangle's transform, then the lower triangle clipped over
        // it: its anti-aliased edge lies over the same picture, so no seam shows on the diagonal.
        g.setTransform(...upper);
        g.drawImage(image, 0, 0);
        g.setTransform(1, 0, 0, 1, 0, 0);
        g.beginPath();
        g.moveTo(...q[0]); g.lineTo(...q[2]); g.lineTo(...q[3]); g.closePath();
        g.clip();
        g.setTransform(...lower);
        g.drawImage(image, 0, 0);
        g.restore();
        ++drawn;
      }
    }
    this.stats.drawn = drawn;
  }
}
