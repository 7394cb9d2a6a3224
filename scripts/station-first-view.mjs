// SPDX-License-Identifier: MIT
// Measures the operator station's first view (docs/operator-station.md, "First view"): for each map,
// `sewerplan serve` on that map alone, the page opened in a new browser context of Debian's headless
// Chromium (software WebGL, SwiftShader), and, in ms after navigation:
//  - first picture: the end of the first frame in which a canvas of the map view was drawn into
//    (a WebGL draw call with something to draw, or a 2-D canvas stroke, fill or image). The page is
//    instrumented from the outside (an init script wrapping the canvases' draw calls), so the same
//    measure holds for any version of the page;
//  - ready: the page's data-ready (its map opened and drawn, as the page itself says);
//  - reacts: the end of the last long task (over 200 ms) before the page stays responsive for 1.5 s
//    (no animation frame later than 200 ms); and the longest task;
//  - first paint: the page's first contentful paint (a loading note in the page's HTML shows then);
//  - loading: when a loading indicator (`#map-loading`) was first seen shown (at the latest when the
//    page's HTML is parsed, after its module scripts ran) and when it was hidden.
// With --deep-zoom, on a map whose overview is an image (lod.js: 'overview' or 'detail'), the view is
// then zoomed in a level at a time, each until drawn, until the window is drawn as vector layers, and
// the longest animation-frame gap of each step is printed (the switch's: until 1.5 s pass after it
// with no frame over 200 ms, since its layers' shaders link and compile a few frames later).
//
//   node scripts/station-first-view.mjs --binary build/release/bin/sewerplan [--web DIR] [--runs N]
//        [--deep-zoom] MAP...
//
// playwright-core is taken from web/node_modules (npm ci in web/). Chromium: /usr/bin/chromium, or
// $CHROMIUM.
import { spawn } from 'node:child_process';
import { readFileSync } from 'node:fs';
import { createRequire } from 'node:module';
import { basename, dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';

const here = dirname(fileURLToPath(import.meta.url));
const { chromium } = createRequire(join(here, '../web/package.json'))('playwright-core');

const args = process.argv.slice(2);
const option = (name, fallback) => {
  const at = args.indexOf(name);
  return at >= 0 ? args.splice(at, 2)[1] : fallback;
};
const flag = (name) => {
  const at = args.indexOf(name);
  return at >= 0 ? (args.splice(at, 1), true) : false;
};
const binary = option('--binary', join(here, '../build/release/bin/sewerplan'));
const web = option('--web', null);
const runs = Number(option('--runs', '3'));
const deepZoom = flag('--deep-zoom');
const maps = args;
if (maps.length === 0) {
  console.error('usage: node scripts/station-first-view.mjs --binary SEWERPLAN [--web DIR] [--runs N] [--deep-zoom] MAP...');
  process.exit(2);
}
const loadavg = () => readFileSync('/proc/loadavg', 'utf8').split(' ').slice(0, 3).join(' ');

// In the page, before its own code: draw calls into the map view's canvases stamped, long tasks and
// animation-frame gaps recorded.
function instrument() {
  const fv = { firstDraw: null, firstDrawKind: null, firstPicture: null, longTasks: [], frames: [], loading: [] };
  window.__firstView = fv;
  const inView = (canvas) => canvas.isConnected && canvas.closest?.('#view');
  const drew = (canvas, kind) => {
    if (fv.firstDraw !== null || !inView(canvas)) return;
    fv.firstDraw = performance.now();
    fv.firstDrawKind = kind;
    // Shown at the end of the frame that drew it: the next frame's start is after it (an upper bound).
    requestAnimationFrame(() => requestAnimationFrame(() => { fv.firstPicture = performance.now(); }));
  };
  for (const Gl of [window.WebGL2RenderingContext, window.WebGLRenderingContext]) {
    if (!Gl) continue;
    for (const name of ['drawArrays', 'drawElements', 'drawArraysInstanced', 'drawElementsInstanced']) {
      const original = Gl.prototype[name];
      if (!original) continue;
      Gl.prototype[name] = function (...a) {
        const count = name.startsWith('drawArrays') ? a[2] : a[1];
        const instances = name.endsWith('Instanced') ? a.at(-1) : 1;
        if (count > 0 && instances > 0) drew(this.canvas, 'webgl');
        return original.apply(this, a);
      };
    }
  }
  for (const name of ['drawImage', 'stroke', 'fill', 'fillRect']) {
    const original = CanvasRenderingContext2D.prototype[name];
    CanvasRenderingContext2D.prototype[name] = function (...a) {
      drew(this.canvas, `2d ${name}`);
      return original.apply(this, a);
    };
  }
  try {
    new PerformanceObserver((list) => {
      for (const e of list.getEntries()) fv.longTasks.push([e.startTime, e.duration]);
    }).observe({ type: 'longtask', buffered: true });
  } catch { /* no long task timing: the frame gaps still say it */ }
  const frame = (t) => { fv.frames.push(t); requestAnimationFrame(frame); };
  requestAnimationFrame(frame);
  // The loading indicator: when it is shown or hidden (polled each frame and on each mutation).
  const watch = () => {
    const el = document.getElementById('map-loading');
    const shown = Boolean(el && el.isConnected && !el.hidden && getComputedStyle(el).display !== 'none');
    if (fv.loading.length === 0 ? shown : fv.loading.at(-1)[1] !== shown) fv.loading.push([performance.now(), shown]);
  };
  new MutationObserver(watch).observe(document, { subtree: true, childList: true, attributes: true });
  document.addEventListener('DOMContentLoaded', watch);
}

function serve(map) {
  const server = spawn(binary, ['serve', '--map', map, '--port', '0', ...(web ? ['--web', web] : [])],
                       { stdio: ['ignore', 'pipe', 'inherit'] });
  const url = new Promise((resolve, reject) => {
    let text = '';
    server.stdout.on('data', (chunk) => {
      text += chunk;
      const match = /http:\/\/\S+/.exec(text);
      if (match) resolve(match[0]);
    });
    server.on('exit', (code) => reject(new Error(`sewerplan serve exited with ${code}`)));
  });
  return { server, url };
}

// One page load of `url`: the figures above, in ms after navigation.
async function firstView(browser, url) {
  const context = await browser.newContext({ viewport: { width: 1280, height: 900 } });
  const page = await context.newPage();
  page.on('pageerror', (e) => console.error('page error:', e.message));
  await page.addInitScript(instrument);
  await page.goto(url);
  await page.waitForSelector('body[data-ready=true]', { timeout: 180000 });
  const ready = await page.evaluate(() => performance.now());
  // Until 1.5 s pass without a frame gap over 200 ms (at most 60 s).
  await page.waitForFunction(() => {
    const f = window.__firstView.frames, now = performance.now();
    if (f.length < 2 || now - f.at(-1) > 200) return false;
    let k = f.length - 1;
    while (k > 0 && f[k] - f[k - 1] <= 200) --k;
    return now - f[k] >= 1500;
  }, null, { timeout: 60000, polling: 100 });
  const fv = await page.evaluate(() => window.__firstView);
  // The page's own marks, where it has them (main.js: its code started, the map asked, its geometry come).
  const marks = await page.evaluate(() => [[`code started`, window.station?.state?.timings?.started_at_ms],
    ...performance.getEntriesByType('mark').filter((m) => /: (asked|geometry come)$/.test(m.name)).map((m) => [m.name, m.startTime])]
    .filter(([, t]) => t !== undefined).map(([n, t]) => `${n} ${Math.round(t)}`).join(', '));
  const gaps = fv.frames.slice(1).map((t, i) => [fv.frames[i], t - fv.frames[i]]).filter(([, d]) => d > 200);
  const lastGap = gaps.at(-1);
  const longest = Math.max(0, ...fv.longTasks.map(([, d]) => d), ...gaps.map(([, d]) => d));
  const reacts = Math.max(lastGap ? lastGap[0] + lastGap[1] : 0, ...fv.longTasks.map(([s, d]) => s + d), fv.firstPicture ?? 0);
  const shown = fv.loading.find(([, s]) => s)?.[0];
  const hidden = fv.loading.findLast(([, s]) => !s)?.[0];
  const fcp = await page.evaluate(() => performance.getEntriesByName('first-contentful-paint')[0]?.startTime ?? null);
  const result = { fcp, firstPicture: fv.firstPicture, kind: fv.firstDrawKind, ready, reacts, longest,
                   loadingShown: shown ?? null, loadingHidden: hidden ?? null, marks };
  return { page, context, result };
}

// Zooms in a level at a time (each until drawn) until the window is drawn as vector layers; the
// longest frame gap of each step, the switch's and the 2 s after it.
async function deepZoom_(page) {
  return page.evaluate(async () => {
    const { view } = window.station;
    const fv = window.__firstView;
    const steps = [];
    for (let level = 0; level < 12 && view.stats.lod.at(-1)?.mode !== 'vector'; ++level) {
      const from = fv.frames.length;
      const t0 = performance.now();
      await window.station.zoomAndWait(1);
      // The switch's layers link asynchronously and draw (and compile) a few frames later: until
      // 1.5 s pass with no frame over 200 ms (at most 60 s).
      if (view.stats.lod.at(-1)?.mode === 'vector') {
        const quietSince = () => {
          const f = fv.frames;
          let k = f.length - 1;
          while (k > from && f[k] - f[k - 1] <= 200) --k;
          return f[k];
        };
        const until = performance.now() + 60000;
        while (performance.now() < until && (fv.frames.length - from < 3 || performance.now() - quietSince() < 1500)) {
          await new Promise((r) => setTimeout(r, 100));
        }
      }
      const f = fv.frames.slice(Math.max(0, from - 1));
      const gaps = f.slice(1).map((t, i) => t - f[i]);
      steps.push({ mode: view.stats.lod.at(-1)?.mode, drawn: view.stats.lod.at(-1)?.drawn,
                   ms: Math.round(performance.now() - t0), maxFrame: Math.round(Math.max(0, ...gaps)) });
    }
    return steps;
  });
}

const r0 = (x) => (x === null || x === undefined ? '-' : Math.round(x));
const browser = await chromium.launch({ executablePath: process.env.CHROMIUM ?? '/usr/bin/chromium', args: ['--no-sandbox'] });
try {
  for (const map of maps) {
    const { server, url } = serve(map);
    const address = await url;
    for (let run = 0; run < runs; ++run) {
      const { page, context, result: r } = await firstView(browser, address);
      console.log(`${basename(map)} run ${run + 1}: first paint ${r0(r.fcp)} ms, first picture ${r0(r.firstPicture)} ms (${r.kind}), ready ${r0(r.ready)} ms, ` +
                  `reacts ${r0(r.reacts)} ms, longest task ${r0(r.longest)} ms; loading shown ${r0(r.loadingShown)} ms, ` +
                  `hidden ${r0(r.loadingHidden)} ms; the page's marks: ${r.marks} (load ${loadavg()})`);
      if (deepZoom && run === 0) {
        const steps = await deepZoom_(page);
        console.log(`${basename(map)} deep zoom: ` + steps.map((s) => `${s.mode} (${s.drawn}) in ${s.ms} ms, ` +
                    `longest frame ${s.maxFrame} ms`).join('; ') + ` (load ${loadavg()})`);
      }
      await context.close();
    }
    server.kill('SIGTERM');
  }
} finally {
  await browser.close();
}
