// SPDX-License-Identifier: MIT
// The station's cases for issue 32's "Findings and the robot's knowledge on the map", called from
// station.test.mjs on its page and server:
//   taskMarkers: after the paper's plan, each task's mark says its kind and its number in the
//     plan's order;
//   learntAfterRun: after the simulation with the obstacle in P4, what the robot learnt is drawn
//     and downloads as the CLI's learnt JSON (which `simulate --learnt` reads) and as GeoJSON;
//   findingsOnTheMap: the ISYBAU street with its condition data uploaded: every finding drawn,
//     classed and ringed by what the risk mode makes of it, the legend, the hover (code, name,
//     class), and the plan's risk beside the plan when blockages are weighed.
import { spawnSync } from 'node:child_process';
import { copyFileSync, readFileSync } from 'node:fs';
import { join } from 'node:path';

const check = (ok, what) => { if (!ok) throw new Error(what); };
// The data of one of the map view's deck.gl layers, as plain values.
const layerData = (page, id) => page.evaluate((i) => {
  const layer = window.station.view.deck.props.layers.find((l) => l?.id === i);
  return layer ? JSON.parse(JSON.stringify(layer.props.data)) : null;
}, id);

export async function taskMarkers(page) {
  const marks = await layerData(page, 'tasks');
  check(marks, 'no task marks drawn');
  const of = (name) => marks.find((m) => m.t.name === name);
  const got = ['sample-1', 'inspect-1', 'end', 'start'].map((n) => of(n) && `${n}:${of(n).kind}:${of(n).label}`);
  console.log(`task marks: ${got.join(' ')}`);
  // The paper's plan takes the sample in P6 first, then inspects P4, then ends in P9.
  check(got.join(' ') === 'sample-1:sample:1 inspect-1:inspection:2 end:end:3 start:start:S',
        `task marks by kind and plan order: ${got.join(' ')}`);
  const labels = await layerData(page, 'task-labels');
  check(labels?.length === marks.length, 'the task marks are not numbered on the map');
  const legend = await page.locator('#overlay-legend').textContent();
  check(/sample.*inspection.*go-to.*end/.test(legend) && /plan order/.test(legend), `the legend of task kinds: ${legend}`);
}

export async function learntAfterRun(page, { binary, ais, out }) {
  await page.waitForFunction(() => window.station.state.learntDoc, null, { timeout: 10000 })
    .catch(() => { throw new Error('nothing learnt shown after the run'); });
  const doc = await page.evaluate(() => window.station.state.learntDoc);
  check(doc.learnt.blockages.length === 1 && doc.learnt.blockages[0].pipe === 'P4',
        `learnt: ${JSON.stringify(doc.learnt)}`);
  const drawn = await layerData(page, 'learnt');
  check(drawn?.some((p) => p.kind === 'blockage' && p.properties.pipe === 'P4'), 'the learnt blockage in P4 is not drawn');
  const summary = await page.locator('#learnt-summary').textContent();
  check(/1 blocked/.test(summary) && /measured \d+ pipes/.test(summary), `learnt summary: ${summary}`);
  const save = async (button) => {
    const [download] = await Promise.all([page.waitForEvent('download'), page.click(button)]);
    const path = join(out, download.suggestedFilename());
    await download.saveAs(path);
    return path;
  };
  const learntPath = await save('#learnt-json');
  const learnt = JSON.parse(readFileSync(learntPath, 'utf8'));
  check(learnt.format === 'sewerplan-learnt' && learnt.blockages[0].pipe === 'P4', `learnt download: ${JSON.stringify(learnt)}`);
  // The CLI reads it for the next mission (and writes it back at the end: a copy).
  const again = join(out, 'learnt-again.json');
  copyFileSync(learntPath, again);
  const cli = spawnSync(binary, ['simulate', '--map', join(ais, 'map.json'), '--mission', join(ais, 'missions/paper.json'),
                                 '--learnt', again, '--quiet'], { encoding: 'utf8' });
  check(cli.status === 0, `simulate --learnt of the download: exit ${cli.status}: ${cli.stderr}`);
  const geo = JSON.parse(readFileSync(await save('#learnt-geojson'), 'utf8'));
  const blocked = geo.features?.find((f) => f.properties.learnt === 'blockage');
  check(geo.type === 'FeatureCollection' && blocked?.geometry.type === 'Point' && blocked.properties.pipe === 'P4',
        `learnt GeoJSON: ${JSON.stringify(geo).slice(0, 300)}`);
  console.log(`learnt: ${summary}; downloads read back (simulate --learnt: exit 0)`);
}

export async function findingsOnTheMap(page, { source }) {
  const isybau = join(source, 'datasets/isybau');
  await page.setInputFiles('#map-upload', join(isybau, 'street-2017.xml'));
  await page.waitForFunction(() => document.body.dataset.opened === 'street-2017', null, { timeout: 30000 });
  await page.selectOption('#profile', 'makro-plus');
  await page.setInputFiles('#condition-upload', join(isybau, 'street-zustand.xml'));
  await page.waitForFunction(() => /^street-2017:impassable:[1-9]/.test(document.body.dataset.findings ?? ''), null, { timeout: 30000 })
    .catch(async () => { throw new Error(`no findings drawn: ${await page.evaluate(() => document.body.dataset.findings)}`); });
  let findings = await layerData(page, 'findings');
  const of = (list, pipe, code) => list.find((f) => f.pipe === pipe && f.code === code);
  const served = Number((await page.evaluate(() => document.body.dataset.findings)).split(':')[2]);
  check(findings?.length === served, `findings drawn: ${findings?.length} of the server's ${served}`);
  check(of(findings, 'S2', 'BAC')?.class === 'impassable' && of(findings, 'S2', 'BAC').planner === 'closed',
        `the collapse in S2: ${JSON.stringify(of(findings, 'S2', 'BAC'))}`);
  check(of(findings, 'S1', 'BBA')?.planner === 'ignored', 'roots weighed though the mode does not weigh');
  // Weighing the possible blockages: the roots are weighed with their probability.
  await page.selectOption('#risk', 'expected');
  await page.waitForFunction(() => /^street-2017:expected:/.test(document.body.dataset.findings ?? ''), null, { timeout: 30000 });
  findings = await layerData(page, 'findings');
  const roots = of(findings, 'S1', 'BBA');
  check(roots?.class === 'blockage' && roots.planner === 'weighed' && Math.abs(roots.probability - 0.3) < 1e-9,
        `the roots in S1 with blockages weighed: ${JSON.stringify(roots)}`);
  const legend = await page.locator('#overlay-legend').textContent();
  check(/impassable/.test(legend) && /closed \(\d+\)/.test(legend) && /weighed by probability \(\d+\)/.test(legend) && /ignored/.test(legend),
        `the findings' legend: ${legend}`);
  // Hovering the roots: their code, the code's name, class and what the planner makes of them.
  const canvas = page.locator('#view #deckgl-overlay');
  const box = await canvas.boundingBox();
  const at = await page.evaluate((f) => window.station.view.project(f.at), roots);
  await page.mouse.move(box.x + at[0], box.y + at[1]);
  await page.waitForFunction(() => /BBA roots/.test(document.querySelector('#hover').textContent), null, { timeout: 5000 })
    .catch(async () => { throw new Error(`hover over the roots: ${await page.locator('#hover').textContent()}`); });
  const hover = await page.locator('#hover').textContent();
  check(/BBA roots \(DIN EN 13508-2\)/.test(hover) && /class blockage, p 0.30/.test(hover) && /weighed by the planner/.test(hover),
        `hover over the roots: ${hover}`);
  console.log(`findings: ${findings.length} drawn; hover: ${hover}`);
  // A plan that passes the attached deposits in S3 (p 0.125) there and back: its risk beside it
  // (as `plan --risk expected`: unobstructed run 0.77, expected cost of stops 75.0 s).
  const mission = {
    format: 'sewerplan-mission', version: 1, name: 'street', profile: 'makro-plus', start: { manhole: 'S3' },
    tasks: [{ name: 'sample', type: 'take_water_sample', at: { pipe: 'S3', offset_m: 30 } },
            { name: 'end', type: 'go_to', at: { manhole: 'S3' }, final: true }],
  };
  await page.setInputFiles('#mission-upload', { name: 'street.json', mimeType: 'application/json', buffer: Buffer.from(JSON.stringify(mission)) });
  await page.waitForFunction(() => window.station.state.mission.name === 'street');
  await page.click('#plan');
  await page.waitForFunction(() => /unobstructed run/.test(document.querySelector('#plan-risk').textContent), null, { timeout: 30000 })
    .catch(async () => { throw new Error(`no plan risk: ${await page.locator('#plan-risk').textContent()} ${await page.locator('#messages').textContent()}`); });
  const risk = await page.locator('#plan-risk').textContent();
  check(/unobstructed run 76\.6 %, expected cost of stops 75\.0 s; 2 possible blockages/.test(risk) && /BBB/.test(risk), `the plan's risk: ${risk}`);
  console.log(`plan risk: ${risk}`);
}
