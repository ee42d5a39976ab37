// Nothing lost, nothing unbounded: presets survive every corruption of their storage and a
// second tab; share links open textures only; oversized and unsupported photos are refused
// before decoding; the Content-Security-Policy holds; the page works offline after one visit
// and without WebGPU.
const { test } = require('@playwright/test');
const fs = require('fs');
const path = require('path');
const zlib = require('zlib');
const { expect, openApp, state, waitFrames, clickWidget, waitAnalyses, ROOT } = require('./helpers');

const SAMPLES = path.join(ROOT, 'www', 'samples');

// Reloads and waits for the app.
async function reload(page) {
  await page.reload();
  await page.waitForFunction(() => window.proctex && window.proctex.ready, null, { timeout: 120_000 });
  await waitFrames(page, 3);
}

// Waits until the app's state satisfies `pred(state)` (polled from here, so that nothing is
// evaluated from a string inside the page, which its CSP forbids).
async function until(page, pred, timeout = 60_000) {
  const end = Date.now() + timeout;
  for (;;) {
    await page.evaluate(() => window.proctex.requestRepaint());
    const s = await state(page);
    if (pred(s)) return s;
    if (Date.now() > end) throw new Error(`timed out; state: ${JSON.stringify({ ...s, widgets: undefined })}`);
    await page.waitForTimeout(100);
  }
}

// Drops `bytes` as a file called `name` on the page.
async function dropBytes(page, bytes, name, type = 'image/png') {
  await page.evaluate(([b, n, t]) => {
    const dt = new DataTransfer();
    dt.items.add(new File([new Uint8Array(b)], n, { type: t }));
    const target = document.getElementById('proctex_canvas');
    target.dispatchEvent(new DragEvent('dragover', { dataTransfer: dt, bubbles: true, cancelable: true }));
    target.dispatchEvent(new DragEvent('drop', { dataTransfer: dt, bubbles: true, cancelable: true }));
  }, [[...bytes], name, type]);
}

// A PNG whose header says `w × h` (1.6 GB decoded for 20000²) but whose data is a few bytes.
function headerOnlyPng(w, h) {
  const crc32 = (buf) => {
    let c = ~0;
    for (const b of buf) {
      c ^= b;
      for (let k = 0; k < 8; k++) c = (c >>> 1) ^ (0xedb88320 & -(c & 1));
    }
    return ~c >>> 0;
  };
  const chunk = (type, data) => {
    const len = Buffer.alloc(4); len.writeUInt32BE(data.length);
    const td = Buffer.concat([Buffer.from(type), data]);
    const crc = Buffer.alloc(4); crc.writeUInt32BE(crc32(td));
    return Buffer.concat([len, td, crc]);
  };
  const ihdr = Buffer.alloc(13);
  ihdr.writeUInt32BE(w, 0); ihdr.writeUInt32BE(h, 4); ihdr[8] = 8; ihdr[9] = 2;
  // One black row where the header promises `h`: a decoder would fail on the missing rows, so
  // an answer naming the size limit can only have come from the header.
  const deflate = zlib.deflateSync(Buffer.alloc(1 + 3 * w), { level: 9 });
  return Buffer.concat([Buffer.from([137, 80, 78, 71, 13, 10, 26, 10]), chunk('IHDR', ihdr),
    chunk('IDAT', deflate), chunk('IEND', Buffer.alloc(0))]);
}

test('an unreadable stored library is kept, can be downloaded, and is never saved over unkept', async ({ page }) => {
  await openApp(page);
  const junk = 'x'.repeat(3e6); // the repro: too big to copy aside within the quota
  await page.evaluate((j) => localStorage.setItem('proctex.presets', j), junk);
  await reload(page);
  let s = await state(page);
  expect(s.presets_notice).toContain('could not be read');
  const backups = await page.evaluate(() => Object.keys(localStorage).filter((k) => k.startsWith('proctex.presets.unreadable-')));
  if (backups.length) {
    // Copied aside: saving may go on, the copy is intact.
    expect(s.presets_locked).toBe(false);
    expect(await page.evaluate((k) => localStorage.getItem(k), backups[0])).toBe(junk);
  } else {
    // Not copied: Save is refused and the original stays, until it is downloaded.
    expect(s.presets_locked).toBe(true);
    await clickWidget(page, 'preset.save');
    await waitFrames(page, 2);
    expect(await page.evaluate(() => localStorage.getItem('proctex.presets'))).toBe(junk);
    s = await state(page);
    expect(s.presets_save_error).toContain('Download it or discard it');
    expect(s.presets).toEqual(['stk_rock_mountain_512']); // kept in this tab meanwhile
  }
  // The notice outlives the start-up analysis (it is not the transient error line).
  await page.waitForTimeout(4000);
  await waitFrames(page, 2);
  expect((await state(page)).presets_notice).not.toBeNull();
  const download = page.waitForEvent('download');
  await clickWidget(page, 'presets.download_unreadable');
  const file = await (await download).path();
  expect(fs.readFileSync(file, 'utf8')).toBe(junk);
  await waitFrames(page, 2);
  expect((await state(page)).presets_locked).toBe(false);
  const before = (await state(page)).presets.length;
  await clickWidget(page, 'preset.save');
  s = await until(page, (s) => s.presets.length === before + 1);
  expect(s.presets_save_error).toBeNull();
  const stored = JSON.parse(await page.evaluate(() => localStorage.getItem('proctex.presets')));
  expect(stored.presets.map((p) => p.name)).toEqual(s.presets);
});

test('one bad preset costs only itself and is named', async ({ page }) => {
  await openApp(page);
  await clickWidget(page, 'preset.save');
  await until(page, (s) => s.presets.length === 1);
  const lib = JSON.parse(await page.evaluate(() => localStorage.getItem('proctex.presets')));
  const bad = JSON.parse(JSON.stringify(lib.presets[0]));
  bad.name = 'the broken one';
  bad.params.transform.scale = -1;
  lib.presets.push(bad);
  await page.evaluate((t) => localStorage.setItem('proctex.presets', t), JSON.stringify(lib));
  await reload(page);
  const s = await state(page);
  expect(s.presets).toEqual(['stk_rock_mountain_512']);
  expect(s.presets_notice).toContain('the broken one');
  expect(s.presets_notice).toContain('transform.scale');
});

test('two tabs saving at once both keep their presets', async ({ context }) => {
  const a = await context.newPage();
  const b = await context.newPage();
  await openApp(a);
  await openApp(b);
  await clickWidget(a, 'preset.save');
  await until(a, (s) => s.presets.length === 1);
  // B hears of A's save through the storage event, and its own save adds to it.
  await until(b, (s) => s.presets.length === 1);
  await clickWidget(b, 'preset.save');
  await until(b, (s) => s.presets.length === 2);
  await until(a, (s) => s.presets.length === 2);
  const stored = JSON.parse(await a.evaluate(() => localStorage.getItem('proctex.presets')));
  expect(stored.presets).toHaveLength(2);
});

test('a share link opens a texture only: a presets library in it is refused', async ({ page, context }) => {
  await openApp(page);
  const params = JSON.parse(await page.evaluate(() => window.proctex.getParams()));
  const library = JSON.stringify({ format: 'proctex-presets/1', presets: [{ name: 'from a link', params }] });
  const link = `/#p=${Buffer.from(library).toString('base64url')}`;
  const other = await context.newPage();
  await other.goto(link);
  await other.waitForFunction(() => window.proctex && window.proctex.ready, null, { timeout: 120_000 });
  await until(other, (s) => s.error !== null);
  const s = await state(other);
  expect(s.error).toContain('links open a texture');
  expect(s.presets).toEqual([]);
  expect(await other.evaluate(() => localStorage.getItem('proctex.presets'))).toBeNull();
});

test('oversized and unsupported photos are refused before decoding, with the limit', async ({ page }) => {
  await openApp(page);
  await dropBytes(page, headerOnlyPng(20000, 20000), 'huge.png');
  await until(page, (s) => s.error !== null);
  let s = await state(page);
  expect(s.error).toContain('huge.png');
  expect(s.error).toContain('16384');
  expect(s.error).not.toMatch(/cannot read|truncat|unexpected end/i); // refused from the header: the rows are missing
  expect(s.photo).toBe('stk_rock_mountain_512.png');
  await page.evaluate(() => window.proctex.requestRepaint());
  await dropBytes(page, headerOnlyPng(9000, 8000), 'wide.png');
  await until(page, (s) => s.error !== null && s.error.includes('wide.png'));
  s = await state(page);
  expect(s.error).toContain('50.0 MP');
  await dropBytes(page, Buffer.from('49492a0008000000', 'hex'), 'scan.tif', 'image/tiff');
  await until(page, (s) => s.error !== null && s.error.includes('scan.tif'));
  expect((await state(page)).error).toContain('TIFF');
});

test('the Content-Security-Policy is in force and the app works under it', async ({ page }) => {
  const violations = [];
  page.on('console', (m) => { if (/Content Security Policy/i.test(m.text())) violations.push(m.text()); });
  await openApp(page);
  const csp = await page.evaluate(() => document.querySelector('meta[http-equiv="Content-Security-Policy"]')?.content);
  expect(csp).toContain("default-src 'self'");
  expect(csp).toContain("script-src 'self' 'wasm-unsafe-eval'");
  // An inline script and a remote connection are blocked.
  const blocked = await page.evaluate(async () => {
    let remote = 'allowed';
    try { await fetch('https://example.com/'); } catch (e) { remote = 'blocked'; }
    return remote;
  });
  expect(blocked).toBe('blocked');
  const n = (await state(page)).analyses;
  await page.evaluate(() => window.proctex.loadSample('skimage_gravel_512.png'));
  await waitAnalyses(page, n + 1);
  expect((await state(page)).error).toBeNull();
  expect(violations.filter((v) => !v.includes('example.com'))).toEqual([]);
});

test('after one visit the page loads and analyses a dropped photo offline', async ({ page, context }) => {
  await openApp(page);
  await page.evaluate(async () => { await navigator.serviceWorker.ready; });
  await page.waitForFunction(() => navigator.serviceWorker.controller !== null, null, { timeout: 60_000 });
  await context.setOffline(true);
  try {
    await reload(page);
    const bytes = fs.readFileSync(path.join(SAMPLES, 'skimage_grass_512.png'));
    const n = (await state(page)).analyses;
    await dropBytes(page, bytes, 'offline_grass.png');
    await waitAnalyses(page, n + 1);
    const s = await state(page);
    expect(s.photo).toBe('offline_grass.png');
    expect(s.error).toBeNull();
  } finally {
    await context.setOffline(false);
  }
});

test('without WebGPU a dropped photo is still analysed, previewed, plotted, exportable and evened out', async ({ page }) => {
  await page.addInitScript(() => { delete Navigator.prototype.gpu; });
  await page.goto('/');
  await page.waitForFunction(() => window.proctex && window.proctex.ready, null, { timeout: 120_000 });
  const notice = await page.locator('#message .text').textContent();
  expect(notice).toContain('no WebGPU');
  expect(notice).not.toMatch(/adapter|wgpu/i);
  await dropBytes(page, fs.readFileSync(path.join(SAMPLES, 'skimage_gravel_512.png')), 'gravel_drop.png');
  await page.waitForFunction(() => window.proctex.cpuPreview?.photo === 'gravel_drop.png', null, { timeout: 120_000 });
  await expect(page.locator('#cpu_plots')).toBeVisible();
  await expect(page.locator('#fallback_status')).toContainText('gravel_drop.png');
  const download = page.waitForEvent('download');
  await page.locator('#fallback_wgsl').click();
  const wgsl = fs.readFileSync(await (await download).path(), 'utf8');
  expect(wgsl).toContain('fn proctex(');
  // The lighting option, as in the app: the photo analysed again with its gradient divided out.
  await expect(page.locator('#fallback_status')).not.toContainText('lighting evened out');
  await page.locator('#fallback_lighting').check();
  await expect(page.locator('#fallback_status')).toContainText('lighting evened out', { timeout: 120_000 });
  await expect(page.locator('#fallback_status')).toContainText('gravel_drop.png');
  await expect(page.locator('#fallback_lighting')).toBeEnabled();
  // A file that is no image is reported in the panel, and the last result stays.
  await dropBytes(page, Buffer.from('not an image'), 'junk.png');
  await expect(page.locator('#fallback_error')).toContainText('junk.png');
});
