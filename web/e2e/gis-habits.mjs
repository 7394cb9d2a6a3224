// SPDX-License-Identifier: MIT
// The station's GIS habits in the browser (issue 32), run by station.test.mjs on its page at the
// end of its flow, with the AIS map open: a pipe found by name and jumped to, fit-to-view, the
// scale bar, a task added, deleted with the Delete key, the deletion undone and redone (Ctrl+Z,
// Ctrl+Y), the coordinates under the pointer in the map's CRS (a georeferenced map uploaded), the
// manholes' names thinned so that none overlaps (a generated 400-manhole network, whose names pile
// up unthinned), a stale mission dropped with a message, and the mission kept across a reload.
import { execFileSync } from 'node:child_process';
import { readFileSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';

export async function gisHabits(page, { binary, source, ais, out, check, shot }) {
  const t0 = Date.now();
  const canvas = page.locator('#view #deckgl-overlay');
  const box = await canvas.boundingBox();
  const aisId = await page.evaluate(() => window.station.state.map.id);
  const blur = () => page.evaluate(() => document.activeElement?.blur());

  // Found by name (any case) and jumped to: centred, marked, named; a name nobody has, said so.
  await page.fill('#search', 'p6');
  await page.press('#search', 'Enter');
  await page.waitForFunction(() => window.station.state.highlight?.name === 'P6', null, { timeout: 10000 });
  const jumped = await page.evaluate(() => {
    const p = window.station.state.map.pipeByName.get('P6');
    const { target } = window.station.view.viewState();
    return { d: Math.hypot(target[0] - (p.from[0] + p.to[0]) / 2, target[1] - (p.from[1] + p.to[1]) / 2),
             note: document.querySelector('#search-note').textContent };
  });
  check(jumped.d < 1e-6 && jumped.note === 'pipe P6', `the search for p6: ${JSON.stringify(jumped)}`);
  await page.fill('#search', 'nowhere');
  await page.press('#search', 'Enter');
  check(await page.locator('#search-note').textContent() === 'no manhole or pipe named nowhere', 'an unknown name is not said');

  // The scale bar: a round length, as wide as the view's zoom makes it.
  const scale = () => page.evaluate(() => ({ zoom: window.station.view.viewState().zoom,
                                             metres: Number(document.querySelector('#scale-bar').dataset.metres),
                                             px: document.querySelector('#scale-bar').getBoundingClientRect().width,
                                             text: document.querySelector('#scale-text').textContent }));

  // Fit: the whole network in view again (the zoom of a map opened).
  await blur();
  await page.click('#fit');
  const fitted = await page.evaluate(() => {
    const [x0, y0, x1, y1] = window.station.state.map.bounds, v = document.querySelector('#view');
    return { zoom: window.station.view.viewState().zoom,
             expected: Math.log2(Math.min(v.clientWidth, v.clientHeight) / (Math.max(x1 - x0, y1 - y0, 1) * 1.1)) };
  });
  check(Math.abs(fitted.zoom - fitted.expected) < 1e-9, `Fit: zoom ${fitted.zoom}, the whole map's ${fitted.expected}`);
  const far = await scale();
  await page.evaluate(() => window.station.zoomAndWait(2));
  const near = await scale();
  await blur();
  await page.keyboard.press('Home');  // Fit's key
  const home = await page.evaluate(() => window.station.view.viewState().zoom);
  check(Math.abs(home - fitted.expected) < 1e-9, `Home: zoom ${home}, the whole map's ${fitted.expected}`);
  for (const s of [near, far]) {
    check(Math.abs(s.px - s.metres * 2 ** s.zoom) < 1.5 && s.px <= 161 && /^[125]0*$/.test(String(s.metres).replace('.', '')),
          `the scale bar: ${JSON.stringify(s)}`);
  }
  check(near.metres < far.metres, `the scale bar did not change with the zoom: ${near.text}, ${far.text}`);
  console.log(`GIS habits: P6 found and centred; Fit, and Home; scale ${near.text} zoomed in, ${far.text} fitted`);

  // A task clicked onto the map is selected; Delete removes it; Ctrl+Z brings it back, Ctrl+Y
  // removes it again, Ctrl+Z once more.
  const tasks = () => page.evaluate(() => window.station.state.mission.tasks.map((t) => t.name));
  const before = await tasks();
  await page.check('input[name=mode][value=sample]');
  const at = await page.evaluate(() => window.station.screenPoint('P6', 0.3));
  await page.mouse.click(box.x + at[0], box.y + at[1]);
  await page.waitForFunction((n) => window.station.state.mission.tasks.length === n + 1, before.length);
  const added = (await tasks()).find((n) => !before.includes(n));
  await page.waitForFunction(() => document.querySelector('#tasks li.selected'));
  const selected = await page.locator('#tasks li.selected').textContent();
  check(selected.startsWith(`${added}:`), `the task added (${added}) is not the one selected: ${selected}`);
  await page.keyboard.press('Delete');
  check(JSON.stringify(await tasks()) === JSON.stringify(before), `Delete left ${await tasks()}`);
  await page.keyboard.press('Control+z');
  check((await tasks()).includes(added), `Ctrl+Z did not bring ${added} back: ${await tasks()}`);
  await page.keyboard.press('Control+y');
  check(!(await tasks()).includes(added), `Ctrl+Y did not remove ${added} again: ${await tasks()}`);
  await page.click('#undo');
  check((await tasks()).includes(added), 'the Undo button did not bring the task back');
  // A task selected in the list by a click, deleted by the key.
  await page.locator('#tasks li').first().click({ position: { x: 5, y: 5 } });
  const first = (await tasks())[0];
  await page.keyboard.press('Delete');
  check(!(await tasks()).includes(first), `the task clicked in the list (${first}) was not deleted`);
  await page.keyboard.press('Control+z');
  const kept = await tasks();
  check(kept.includes(first) && kept.includes(added), `undo after the list's delete: ${kept}`);
  console.log(`GIS habits: ${added} added, deleted (Delete), undone, redone, undone; ${first} deleted from the list and undone`);

  // The coordinates under the pointer: the AIS map names no CRS; a copy that names EPSG:25832.
  const coordsAt = async (manhole) => {
    const p = await page.evaluate((n) => window.station.manholePoint(n), manhole);
    await page.mouse.move(box.x + p[0], box.y + p[1]);
    return page.evaluate((n) => {
      const line = document.querySelector('#coords');
      const m = window.station.state.map.manholeByName.get(n);
      return { text: line.textContent, dx: Number(line.dataset.x) - m.position[0], dy: Number(line.dataset.y) - m.position[1],
               pixel: 2 ** -window.station.view.viewState().zoom };
    }, manhole);
  };
  const aisManhole = await page.evaluate(() => window.station.state.map.manhole(0).name);
  const local = await coordsAt(aisManhole);
  check(Math.hypot(local.dx, local.dy) < 2 * local.pixel && local.text.endsWith('(local metres: the map names no CRS)'),
        `the coordinates over ${aisManhole}: ${JSON.stringify(local)}`);
  await page.click('#export-geojson');
  await page.waitForFunction(() => /names no coordinate reference system/.test(document.querySelector('#search-note').textContent));
  const map = JSON.parse(readFileSync(join(ais, 'map.json'), 'utf8'));
  map.crs = 'EPSG:25832';
  for (const m of map.manholes) { m.x_m += 360000; m.y_m += 5620000; }
  await page.setInputFiles('#map-upload', { name: 'utm.json', mimeType: 'application/json', buffer: Buffer.from(JSON.stringify(map)) });
  await page.waitForFunction(() => document.body.dataset.opened === 'utm', null, { timeout: 30000 });
  const utm = await coordsAt(aisManhole);
  const m0 = map.manholes.find((m) => m.name === aisManhole);
  check(Math.hypot(utm.dx, utm.dy) < 2 * utm.pixel && utm.text.endsWith('EPSG:25832') &&
        utm.text.startsWith(`x ${String(Math.trunc(m0.x_m))}`), `the coordinates over ${aisManhole} in UTM: ${JSON.stringify(utm)}`);
  console.log(`GIS habits: the pointer over ${aisManhole}: ${local.text}; on the UTM copy: ${utm.text}`);

  // The GeoJSON export of the UTM copy: the mission, the plan's route and a replayed log's trace,
  // the same features as `sewerplan export-geojson` writes from the same files.
  const utmFile = join(out, 'utm.json');
  writeFileSync(utmFile, JSON.stringify(map));
  // (Under other names: the inputs hold paper.json and demo.jsonl from station.test.mjs, and the
  // same file set again fires no change.)
  await page.setInputFiles('#mission-upload', { name: 'paper-utm.json', mimeType: 'application/json',
                                                buffer: readFileSync(join(ais, 'missions/paper.json')) });
  await page.waitForFunction(() => window.station.state.mission.name === 'paper-section-6');
  await page.click('#plan');
  await page.waitForFunction(() => window.station.state.planText, null, { timeout: 30000 });
  const planText = await page.evaluate(() => window.station.state.planText);
  const log = join(source, 'tests/data/events/demo.jsonl');
  await page.setInputFiles('#replay-upload', { name: 'demo-utm.jsonl', mimeType: 'application/octet-stream',
                                               buffer: readFileSync(log) });
  await page.waitForFunction(() => window.station.state.outcome && window.station.player.idle, null, { timeout: 30000 });
  const [saved] = await Promise.all([page.waitForEvent('download'), page.click('#export-geojson')]);
  const exported = JSON.parse(readFileSync(await saved.path(), 'utf8'));
  writeFileSync(join(out, 'utm.plan'), planText);
  execFileSync(binary, ['export-geojson', '--map', utmFile, '--mission', join(ais, 'missions/paper.json'),
                        '--plan', join(out, 'utm.plan'), '--log', log, '-o', join(out, 'utm-cli.geojson')]);
  const cli = JSON.parse(readFileSync(join(out, 'utm-cli.geojson'), 'utf8'));
  const layers = new Set(exported.features.map((f) => f.properties.layer));
  check(layers.has('planned_route') && layers.has('driven_route') && layers.has('task'), `the export's layers: ${[...layers]}`);
  check(JSON.stringify(exported) === JSON.stringify(cli), 'the page\'s GeoJSON is not what export-geojson writes from the same files');
  console.log(`GIS habits: GeoJSON exported (${exported.features.length} features: ${[...layers].join(', ')}), as export-geojson's`);

  // Names thinned: a 400-manhole network, fitted, whose names overlap unthinned; drawn, none
  // overlaps another (measured as the page's font draws them); zoomed in, more are drawn.
  const generated = join(out, 'names-400.json');
  execFileSync(binary, ['generate', '--manholes', '400', '--seed', '3', '-o', generated]);
  await page.setInputFiles('#map-upload', generated);
  await page.waitForFunction(() => document.body.dataset.opened === 'names-400', null, { timeout: 30000 });
  const labels = () => page.evaluate(() => {
    const { zoom, manholes } = window.station.view.labels();
    const g = document.createElement('canvas').getContext('2d');
    g.font = '11px monospace';
    const boxes = (list) => list.map((m) => {
      const s = 2 ** window.station.view.viewState().zoom, w = g.measureText(m.name).width;
      return [m.position[0] * s - w / 2, m.position[1] * s - 6.5, m.position[0] * s + w / 2, m.position[1] * s + 6.5];
    });
    const overlapping = (b) => {
      let n = 0;
      for (let i = 0; i < b.length; ++i) {
        for (let j = i + 1; j < b.length; ++j) {
          if (b[i][0] < b[j][2] && b[j][0] < b[i][2] && b[i][1] < b[j][3] && b[j][1] < b[i][3]) ++n;
        }
      }
      return n;
    };
    const all = window.station.state.map.manholes;
    return { zoom, shown: manholes.length, all: all.length, overlapping: overlapping(boxes(manholes)),
             unthinned: overlapping(boxes(all)) };
  });
  const fit400 = await labels();
  await page.evaluate(() => window.station.zoomAndWait(1.5));
  const zoomed = await labels();
  console.log(`GIS habits: names on 400 manholes, fitted: ${fit400.shown} drawn, ${fit400.overlapping} overlapping ` +
              `(all ${fit400.all}: ${fit400.unthinned} overlapping pairs); 1.5 levels in: ${zoomed.shown} drawn, ${zoomed.overlapping} overlapping`);
  check(fit400.unthinned > 0, 'the generated network\'s names do not overlap unthinned: the check would not fail');
  check(fit400.shown > 0 && fit400.overlapping === 0 && zoomed.overlapping === 0, `names overlap: ${JSON.stringify([fit400, zoomed])}`);
  check(zoomed.shown > fit400.shown, `zoomed in, no more names drawn: ${fit400.shown}, ${zoomed.shown}`);
  await shot('12-names-thinned.png');

  // A mission saved for another map of the same ID (here: made up, of 3 manholes) is dropped, saying so.
  await page.evaluate(() => localStorage.setItem('sewerplan-mission:utm', JSON.stringify({
    map: { manholes: 3, pipes: 2, bounds: [0, 0, 1, 1] }, saved: '2026-01-01',
    mission: { format: 'sewerplan-mission', version: 1, name: 'old', tasks: [] } })));
  await page.selectOption('#map', 'utm');
  await page.waitForFunction(() => document.body.dataset.opened === 'utm', null, { timeout: 30000 });
  const dropped = await page.locator('#messages').textContent();
  check(/^The mission saved for map utm on 2026-01-01 was dropped: it was for another map of that ID \(3 manholes, 2 pipes; this one has \d+ and \d+\)$/.test(dropped),
        `a stale mission's message: ${dropped}`);
  check(await page.evaluate(() => window.station.state.mission.tasks.length === 0), 'the stale mission was not dropped');

  // The AIS map's mission, as edited above, kept across a reload.
  await page.selectOption('#map', aisId);
  await page.waitForFunction((i) => document.body.dataset.opened === i, aisId, { timeout: 30000 });
  const mission = await page.evaluate(() => JSON.stringify(window.station.state.mission));
  check(JSON.parse(mission).tasks.length === kept.length, `the AIS mission after reopening: ${mission}`);
  await page.reload();
  await page.waitForSelector('body[data-ready=true]', { timeout: 90000 });
  const reloaded = await page.evaluate(() => JSON.stringify(window.station.state.mission));
  check(reloaded === mission, `after a reload the mission is ${reloaded}, was ${mission}`);
  check(await page.locator('#tasks li').count() === kept.length, 'the reloaded mission\'s tasks are not listed');
  console.log(`GIS habits: the AIS mission (${kept.length} tasks) kept across a reload; a stale one dropped: ${dropped}; ${Date.now() - t0} ms`);
}
