// SPDX-License-Identifier: MIT
// End-to-end: `sewerplan serve` on the AIS test environment, the page in Debian's headless
// Chromium (playwright-core, no bundled browser). Clicks the paper's mission onto the map (start
// in P12, the sample in P6, the inspection of P4, the end in P9), plans, and checks that the route
// and the steps appear. Saves a screenshot of each step beside OUT (default: web/e2e-out/).
//
//   node e2e/station.test.mjs SEWERPLAN_BINARY SOURCE_DIR [OUT_DIR]
import { spawn } from 'node:child_process';
import { mkdirSync } from 'node:fs';
import { join } from 'node:path';
import { chromium } from 'playwright-core';

const [binary, source, out = 'e2e-out'] = process.argv.slice(2);
if (!binary || !source) {
  console.error('usage: node e2e/station.test.mjs SEWERPLAN_BINARY SOURCE_DIR [OUT_DIR]');
  process.exit(2);
}
mkdirSync(out, { recursive: true });

const server = spawn(binary, ['serve', '--map', join(source, 'datasets/ais-testbed/map.json'),
                              '--port', '0', ...process.env.SEWERPLAN_WEB_DIR ? ['--web', process.env.SEWERPLAN_WEB_DIR] : []],
                     { stdio: ['ignore', 'pipe', 'inherit'] });
const url = await new Promise((resolve, reject) => {
  let text = '';
  server.stdout.on('data', (chunk) => {
    text += chunk;
    const match = /http:\/\/\S+/.exec(text);
    if (match) resolve(match[0]);
  });
  server.on('exit', (code) => reject(new Error(`sewerplan serve exited with ${code}`)));
});

const browser = await chromium.launch({
  executablePath: process.env.CHROMIUM ?? '/usr/bin/chromium',
  args: ['--no-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader'],
});
let failed = false;
try {
  const page = await browser.newPage({ viewport: { width: 1280, height: 800 } });
  page.on('pageerror', (e) => console.error('page error:', e.message));
  page.on('console', (m) => m.type() === 'error' && console.error('console:', m.text()));
  const t0 = Date.now();
  await page.goto(url);
  console.log(`page loaded: ${Date.now() - t0} ms`);
  await page.waitForSelector('body[data-ready=true]', { timeout: 90000 });
  console.log(`page load and first draw (AIS map): ${Date.now() - t0} ms`);
  await page.screenshot({ path: join(out, '1-map.png') });

  // Clicks the middle of a pipe (where the page's view projects it) in the given mode.
  async function clickPipe(mode, name, fraction = 0.5) {
    await page.check(`input[name=mode][value=${mode}]`);
    const point = await page.evaluate(([n, f]) => window.station.screenPoint(n, f), [name, fraction]);
    const box = await page.locator('#view canvas').boundingBox();
    const before = await page.evaluate(() => JSON.stringify(window.station.state.mission));
    await page.mouse.move(box.x + point[0], box.y + point[1]);  // hover first, as a user does
    await page.mouse.click(box.x + point[0], box.y + point[1], { delay: 50 });
    await page.waitForFunction((b) => JSON.stringify(window.station.state.mission) !== b, before,
                               { timeout: 10000 });
  }
  await clickPipe('start', 'P12');
  await clickPipe('sample', 'P6');
  await clickPipe('inspect', 'P4');
  await clickPipe('end', 'P9');
  const tasks = await page.locator('#tasks li').allTextContents();
  console.log('tasks:', tasks);
  if (tasks.length !== 3) throw new Error(`expected 3 tasks from the clicks, got ${tasks.length}`);
  await page.screenshot({ path: join(out, '2-mission.png') });

  const t1 = Date.now();
  await page.click('#plan');
  await page.waitForSelector('#steps li', { timeout: 30000 });
  console.log(`plan round trip through the page: ${Date.now() - t1} ms`);
  const steps = await page.locator('#steps li').allTextContents();
  console.log(`${steps.length} steps:`, steps.join(' | '));
  if (!steps.some((s) => s.startsWith('TAKE_WATER_SAMPLE P6'))) throw new Error('no sample in P6');
  if (!steps.some((s) => s.startsWith('INSPECT') && s.includes('P4'))) throw new Error('no inspection of P4');
  const route = await page.evaluate(() => [...window.station.state.route]);
  if (!route.includes('P12') || !route.includes('P9')) throw new Error(`route ${route} misses P12 or P9`);
  await page.screenshot({ path: join(out, '3-plan.png') });
  console.log('station e2e: ok');
} catch (e) {
  failed = true;
  console.error('station e2e: FAILED:', e.message);
  await browser.contexts()[0]?.pages()[0]?.screenshot({ path: join(out, 'failed.png') });
} finally {
  await browser.close();
  server.kill('SIGTERM');
}
process.exit(failed ? 1 : 0);
