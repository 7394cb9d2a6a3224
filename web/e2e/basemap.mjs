// SPDX-License-Identifier: MIT
// The optional basemap in the browser test (station.test.mjs starts `serve --tiles DIR` with the
// tiles written here): off by default, nothing asked or fetched while it is off; on, a map without
// a CRS says so and asks nothing; on a map in ETRS89 / UTM 32N (the AIS map moved near Bonn:
// gis-habits.mjs uploads it as "utm") the tiles are asked, fetched from the station and drawn under
// the network; off again, none is drawn and none asked however the view moves.
import { mkdirSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { deflateSync } from 'node:zlib';

// Where the UTM copy lies: tiles of level 18 around x 136181, y 88088 (its centre, x 360016,
// y 5620012 in EPSG:25832, is in that tile; the server's placement says which it asks for, and the
// test fails if any tile it asks is not here).
const kZoom = 18, kColumns = [136179, 136183], kRows = [88086, 88090];
export const kTileColour = [250, 214, 120];

// A 256 x 256 PNG of one colour with a darker frame (the tiles' seams show in the screenshot).
function png([r, g, b]) {
  const crcTable = Array.from({ length: 256 }, (_, n) => {
    let c = n;
    for (let k = 0; k < 8; ++k) c = c & 1 ? 0xedb88320 ^ (c >>> 1) : c >>> 1;
    return c >>> 0;
  });
  const crc = (bytes) => {
    let c = 0xffffffff;
    for (const byte of bytes) c = crcTable[(c ^ byte) & 0xff] ^ (c >>> 8);
    return (c ^ 0xffffffff) >>> 0;
  };
  const chunk = (type, data) => {
    const body = Buffer.concat([Buffer.from(type, 'ascii'), data]);
    const out = Buffer.alloc(body.length + 8);
    out.writeUInt32BE(data.length, 0);
    body.copy(out, 4);
    out.writeUInt32BE(crc(body), body.length + 4);
    return out;
  };
  const side = 256, rows = Buffer.alloc((side * 3 + 1) * side);
  for (let y = 0; y < side; ++y) {
    for (let x = 0; x < side; ++x) {
      const edge = x < 2 || y < 2 || x >= side - 2 || y >= side - 2;
      rows.set(edge ? [r / 2, g / 2, b / 2] : [r, g, b], y * (side * 3 + 1) + 1 + x * 3);
    }
  }
  const header = Buffer.alloc(13);
  header.writeUInt32BE(side, 0);
  header.writeUInt32BE(side, 4);
  header.set([8, 2, 0, 0, 0], 8);  // 8 bits, RGB
  return Buffer.concat([Buffer.from([137, 80, 78, 71, 13, 10, 26, 10]), chunk('IHDR', header),
                        chunk('IDAT', deflateSync(rows)), chunk('IEND', Buffer.alloc(0))]);
}

// Writes the tiles into DIR/18/X/Y.png; returns DIR.
export function writeTiles(dir) {
  const tile = png(kTileColour);
  for (let x = kColumns[0]; x <= kColumns[1]; ++x) {
    mkdirSync(join(dir, String(kZoom), String(x)), { recursive: true });
    for (let y = kRows[0]; y <= kRows[1]; ++y) writeFileSync(join(dir, String(kZoom), String(x), `${y}.png`), tile);
  }
  return dir;
}

// The basemap's requests (its placements and tiles) that `page` has made: watch from the start.
export function watchBasemapRequests(page) {
  const asked = [];
  page.on('request', (r) => { if (/\/api\/(tiles\/|maps\/[^/]+\/basemap\?)/.test(r.url())) asked.push(r.url()); });
  return asked;
}

export async function basemapCase(page, { asked, check, shot }) {
  const t0 = Date.now();
  check(asked.length === 0, `with the basemap off (the default), the page asked ${asked.slice(0, 3).join(', ')}`);
  check(!(await page.isChecked('#basemap')), 'the basemap is on by default');
  const aisId = await page.evaluate(() => window.station.state.map.id);
  const open = async (id) => {
    await page.selectOption('#map', id);
    await page.waitForFunction((i) => document.body.dataset.opened === i, id, { timeout: 30000 });
  };
  // The under canvas's pixel at the view's top left corner, where no pipe is (device pixels).
  const corner = () => page.evaluate(() => {
    const canvas = document.querySelector('#view canvas');
    return [...canvas.getContext('2d').getImageData(4, 4, 1, 1).data];
  });

  // On, over a map that names no CRS: said, nothing asked.
  await page.check('#basemap');
  const note = await page.locator('#basemap-note').textContent();
  check(/names no coordinate reference system/.test(note), `the basemap's note on ${aisId}: ${note}`);
  await page.evaluate(() => window.station.zoomAndWait(0.5));
  check(asked.length === 0, `the basemap on a map without a CRS asked ${asked.join(', ')}`);

  // The UTM copy: its tiles asked, fetched from the station and drawn under the network.
  await open('utm');
  await page.waitForFunction(() => window.station.basemap.stats.drawn > 0 || window.station.basemap.stats.failed.length > 0,
                             null, { timeout: 30000 });
  const stats = await page.evaluate(() => ({ ...window.station.basemap.stats, note: window.station.basemap.note }));
  check(stats.failed.length === 0, `basemap tiles failed: ${stats.failed.join(', ')} (${stats.note})`);
  const tiles = asked.filter((u) => u.includes('/api/tiles/'));
  check(asked.some((u) => u.includes('/api/maps/utm/basemap?')) && tiles.length > 0 &&
        tiles.every((u) => /\/api\/tiles\/18\/\d+\/\d+\.png$/.test(u)), `the basemap's requests: ${asked.join(', ')}`);
  await page.waitForFunction(() => window.station.view.whenDrawn().then(() => true));
  const drawn = await corner();
  check(drawn.slice(0, 3).every((v, i) => Math.abs(v - kTileColour[i]) <= 2) && drawn[3] === 255,
        `under the network at the view's corner: ${drawn}, not the tile's colour ${kTileColour}`);
  await shot('13-basemap.png');
  console.log(`basemap: ${stats.placements} placements asked, ${tiles.length} tiles fetched, ${stats.drawn} drawn (${Date.now() - t0} ms)`);

  // Off: none drawn, and none asked however the view moves.
  await page.uncheck('#basemap');
  const before = asked.length;
  await page.evaluate(() => window.station.zoomAndWait(-1));
  await page.evaluate(() => window.station.view.whenDrawn());
  const off = await page.evaluate(() => window.station.basemap.stats.drawn);
  const cleared = await corner();
  check(off === 0 && cleared[3] === 0, `the basemap off still draws ${off} tiles (corner ${cleared})`);
  check(asked.length === before, `the basemap off asked ${asked.slice(before).join(', ')}`);
  await open(aisId);
}
