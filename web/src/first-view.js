// SPDX-License-Identifier: MIT
// A map's first view: a picture of the network drawn at once on a 2-D canvas, and a "loading" note
// until the map reacts, while deck.gl's WebGL layers get ready. Without a GPU (Chromium's
// SwiftShader, on the CPU) the first frame that draws a layer type holds the page's main thread for
// seconds while its shaders are compiled (3.5 to 9 s for the AIS map's layers at load 10 to 18), and
// before this the page showed nothing meanwhile. So, for each map opened:
//  1. picture: the network is drawn on this module's canvas (canvas 2D, on the main thread) at the
//     view, the moment the map's geometry is read: each pipe and manhole as the layers draw them
//     (lod.js's widths, radii and colours) on a map of up to kDetailBudget pipes; beyond, every
//     pipe as a thin line and the exits only, as lod.js's overview shows them;
//  2. deck.gl is not even started (LaterDeck) until that picture has been shown (two animation
//     frames after it), so that its WebGL start and its compile come after it, not before;
//  3. then the layers, with a warm-up: one transparent line and one transparent circle, drawn as a
//     vector window's pipes and manholes are (lod.js's vectorData: the same layers, attributes and
//     units), so that their shaders are compiled now, under the note, and not at the first deep zoom
//     of a large map whose overview is an image (a frame of 4.3 s at load 18 before);
//  4. once every layer's shaders are linked and have drawn, and two more frames ran (the main
//     thread free again), the picture and the note go: the map reacts.
// The picture follows the view meanwhile (a pan or a zoom redraws it).
import { Deck } from '@deck.gl/core';
import { LineLayer, ScatterplotLayer } from '@deck.gl/layers';
import { drawNetwork } from './first-picture.js';

// deck.gl's Deck, made only when make() is called (once the first picture is on screen): its
// WebGL start (the context, its first drawing buffer) holds the page's main thread for 0.5 to 2 s
// without a GPU, which came before the first picture when the Deck was made with the page. Until
// made, its props are kept (setProps merges them), a redraw is nothing to do and the view has no
// viewport; made, each call is the Deck's.
export class LaterDeck {
  #props;
  #deck = null;

  constructor(props) { this.#props = { ...props }; }

  // The Deck, made now if it was not.
  make() {
    this.#deck ??= new Deck(this.#props);
    return this.#deck;
  }

  get made() { return this.#deck !== null; }
  get props() { return this.#deck ? this.#deck.props : this.#props; }
  setProps(props) { if (this.#deck) this.#deck.setProps(props); else Object.assign(this.#props, props); }
  redraw(reason) { this.#deck?.redraw(reason); }
  getViewports() { return this.#deck ? this.#deck.getViewports() : []; }
  // Every layer deck.gl holds, the sublayers of composite ones (a TextLayer's) included.
  layers() { return this.#deck?.layerManager?.getLayers() ?? []; }
}

// The warm-up layers: one transparent line and one transparent circle at `at`, as lod.js's
// vectorData gives a vector window's pipes and manholes to the map view's layers (binary columns,
// positions in double precision, pixel units), so that deck.gl compiles the same shaders.
export function warmUpLayers(at) {
  const position = new Float64Array([at[0], at[1], 0]);
  const pipes = { length: 1, attributes: { getSourcePosition: { value: position, size: 3 },
                                           getTargetPosition: { value: position.slice(), size: 3 },
                                           getColor: { value: new Uint8Array(4), size: 4 },
                                           getWidth: { value: new Float32Array([1]), size: 1 } } };
  const manholes = { length: 1, attributes: { getPosition: { value: position.slice(), size: 3 },
                                              getRadius: { value: new Float32Array([1]), size: 1 },
                                              getFillColor: { value: new Uint8Array(4), size: 4 } } };
  return [new LineLayer({ id: 'warm-up-pipes', data: pipes, widthUnits: 'pixels' }),
          new ScatterplotLayer({ id: 'warm-up-manholes', data: manholes, radiusUnits: 'pixels' })];
}

// Whether every model of these (initialized) layers has its shaders linked.
export function layersLinked(layers) {
  return layers.every((layer) => {
    let models;
    try { models = layer.getModels(); } catch { return false; }
    return layer.isLoaded !== false && models.every((m) => m.pipeline?.linkStatus === 'success');
  });
}

// The first view of the map view in `parent`: its canvas (put after `below`, under deck.gl's) and
// the note (`#map-loading` in the page, or one made here). stats: when the picture was drawn, how
// long it took, when the layers were given to deck.gl and when the map reacted (performance.now()).
export class FirstView {
  #canvas;
  #note;
  #phase = 'none';  // 'picture' (shown, deck.gl given nothing), 'layers' (given, compiling), 'done'
  #shown = false;   // the picture has been on screen
  #drawn = null;    // {columns, classes, view} of the picture drawn
  #onShown = null;

  constructor(parent, below) {
    this.#canvas = document.createElement('canvas');
    this.#canvas.id = 'map-first-picture';
    Object.assign(this.#canvas.style, { position: 'absolute', left: '0', top: '0', width: '100%', height: '100%',
                                        pointerEvents: 'none' });
    below.after(this.#canvas);
    this.#note = parent.querySelector('#map-loading');
    if (!this.#note) {
      this.#note = Object.assign(document.createElement('div'), { id: 'map-loading', textContent: 'Loading the map…' });
      this.#note.setAttribute('role', 'status');
      parent.append(this.#note);
    }
    this.stats = { maps: [] };
  }

  // Whether deck.gl is still to be given nothing (the picture is not on screen yet).
  get holding() { return this.#phase === 'picture' && !this.#shown; }

  // Says `text` in the note (and shows it).
  say(text) {
    this.#note.textContent = text;
    this.#note.hidden = false;
  }

  // A new map: draws its picture at the view now; onShown() once it is on screen (the layers may
  // then be given to deck.gl).
  start(columns, classes, view, onShown) {
    const t0 = performance.now();
    this.#phase = 'picture';
    this.#shown = false;
    this.#onShown = onShown;
    this.#canvas.hidden = false;
    const drawn = this.#draw(columns, classes, view);
    const entry = { picture_ms: performance.now() - t0, picture_at: performance.now(), ...drawn };
    this.stats.maps.push(entry);
    this.say('Drawing the map… it reacts when this note goes');
    requestAnimationFrame(() => requestAnimationFrame(() => {
      if (this.#onShown !== onShown) return;  // another map started meanwhile
      this.#shown = true;
      this.#phase = 'layers';
      entry.layers_at = performance.now();
      onShown();
    }));
  }

  // The layers to give deck.gl for `layers`: none while the picture is not on screen yet; the
  // warm-up's with them until the map reacts.
  layers(layers, at) {
    if (this.holding) return [];
    return this.#phase === 'layers' ? [...layers, ...warmUpLayers(at)] : layers;
  }

  // After each deck.gl frame with `layers` (every layer it holds, sublayers included): once all are
  // linked (they drew in this frame), the picture and the note go two frames later.
  afterRender(layers) {
    if (this.#phase !== 'layers' || !layersLinked(layers)) return false;
    this.#phase = 'done';
    const entry = this.stats.maps.at(-1);
    entry.linked_at = performance.now();
    requestAnimationFrame(() => requestAnimationFrame(() => {
      if (this.#phase !== 'done') return;
      this.#canvas.hidden = true;
      this.#note.hidden = true;
      entry.reacts_at = performance.now();
    }));
    return true;  // the layers are to be given again, without the warm-up
  }

  // Redraws the picture for a moved view while it is shown.
  follow(view) {
    const d = this.#drawn;
    if (this.#canvas.hidden || !d || (d.view.zoom === view.zoom && d.view.target[0] === view.target[0] &&
                                      d.view.target[1] === view.target[1])) return;
    this.#draw(d.columns, d.classes, view);
  }

  #draw(columns, classes, view) {
    const c = this.#canvas, dpr = devicePixelRatio;
    const width = Math.round(c.clientWidth * dpr), height = Math.round(c.clientHeight * dpr);
    if (c.width !== width || c.height !== height) Object.assign(c, { width, height });
    this.#drawn = { columns, classes, view: { target: [...view.target], zoom: view.zoom } };
    return drawNetwork(c.getContext('2d'), columns, classes, view, width, height, dpr);
  }
}
