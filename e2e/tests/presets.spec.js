// Presets: saved with the mouse, they survive a reload; a corrupt import changes nothing; the
// morph between two presets follows the t slider dragged with the mouse.
const { test } = require('@playwright/test');
const { expect, openApp, state, waitFrames, reveal, clickWidget, waitAnalyses, morphRockToGrass } = require('./helpers');

const core = (p) => ({ colour: p.colour, transform: p.transform, model: p.model, seed: p.seed });

test('presets survive a reload and a corrupt import leaves them untouched', async ({ page }) => {
  await openApp(page);
  await clickWidget(page, 'preset.save');
  await page.waitForFunction(() => window.proctex.state().presets.length === 1);
  const stored = await page.evaluate(() => window.proctex.getPresets());
  expect(JSON.parse(stored).presets[0].name).toBe('stk_rock_mountain_512');

  await page.reload();
  await page.waitForFunction(() => window.proctex && window.proctex.ready, null, { timeout: 120_000 });
  await waitFrames(page, 2);
  expect((await state(page)).presets).toEqual(['stk_rock_mountain_512']);

  const corrupt = JSON.stringify({
    format: 'proctex-presets/1',
    presets: [{ name: 'broken', params: { format: 'proctex/1', seed: 1 } }],
  });
  await page.evaluate((t) => window.proctex.importPresets(t), corrupt);
  await page.waitForFunction(() => {
    window.proctex.requestRepaint();
    return window.proctex.state().error !== null;
  });
  const s = await state(page);
  expect(s.error).toContain('Import');
  expect(s.error).toContain('presets[0] (broken)');
  expect(s.presets).toEqual(['stk_rock_mountain_512']);
  expect(await page.evaluate(() => window.proctex.getPresets())).toBe(stored);
});

test('morphing two presets follows the t slider', async ({ page }) => {
  await openApp(page);
  const { rock, grass } = await morphRockToGrass(page);
  expect(core(JSON.parse(await page.evaluate(() => window.proctex.getParams())))).toEqual(core(rock));
  // Drag the t slider's knob to the right end with the mouse.
  const [x, y, , h] = await reveal(page, 'morph.t');
  await page.mouse.move(x + 3, y + h / 2);
  await page.mouse.down();
  await page.mouse.move(x + 50, y + h / 2, { steps: 4 });
  await waitFrames(page, 1);
  const mid = await state(page);
  expect(mid.morph_t).toBeGreaterThan(0.2);
  expect(mid.morph_t).toBeLessThan(0.8);
  await page.mouse.move(x + 200, y + h / 2, { steps: 4 });
  await page.mouse.up();
  await waitFrames(page, 2);
  expect((await state(page)).morph_t).toBe(1);
  expect(core(JSON.parse(await page.evaluate(() => window.proctex.getParams())))).toEqual(core(grass));
});

test('a share link restores the texture; params JSON pasted or dropped is re-imported', async ({ page, context }) => {
  await openApp(page);
  const p = JSON.parse(await page.evaluate(() => window.proctex.getParams()));
  p.colour.contrast = 1.7;
  p.transform.rotation_deg = 21;
  const edited = JSON.stringify(p, null, 2);
  await page.evaluate((j) => window.proctex.setParams(j), edited);
  await waitFrames(page, 2);
  const link = await page.evaluate(() => window.proctex.shareLink());
  expect(link).toMatch(/#p=[A-Za-z0-9_-]+$/);

  const other = await context.newPage();
  await other.goto(link);
  await other.waitForFunction(() => window.proctex && window.proctex.ready, null, { timeout: 120_000 });
  await waitFrames(other, 3);
  expect(core(JSON.parse(await other.evaluate(() => window.proctex.getParams())))).toEqual(core(p));
  await other.close();

  // Paste the JSON text, then drop it as a file: each time the params come back.
  for (const how of ['paste', 'drop']) {
    await page.evaluate(() => window.proctex.loadSample('skimage_grass_512.png'));
    await waitFrames(page, 2);
    expect(core(JSON.parse(await page.evaluate(() => window.proctex.getParams())))).not.toEqual(core(p));
    await page.evaluate(([j, h]) => {
      const dt = new DataTransfer();
      if (h === 'paste') {
        dt.setData('text/plain', j);
        document.dispatchEvent(new ClipboardEvent('paste', { clipboardData: dt, bubbles: true, cancelable: true }));
      } else {
        dt.items.add(new File([j], 'texture.json', { type: 'application/json' }));
        document.getElementById('proctex_canvas').dispatchEvent(
          new DragEvent('drop', { dataTransfer: dt, bubbles: true, cancelable: true }));
      }
    }, [edited, how]);
    await page.waitForFunction((c) => {
      window.proctex.requestRepaint();
      return JSON.parse(window.proctex.getParams()).colour.contrast === c;
    }, 1.7, { polling: 100 });
    expect(core(JSON.parse(await page.evaluate(() => window.proctex.getParams())))).toEqual(core(p));
  }
});

test('the built-in gallery holds every sample and loads its analysis', async ({ page }) => {
  await openApp(page);
  await page.waitForFunction(() => {
    window.proctex.requestRepaint();
    return window.proctex.galleryReady && window.proctex.state().gallery.length === 6;
  }, null, { polling: 200, timeout: 120_000 });
  await waitFrames(page, 2);
  expect((await state(page)).gallery[4]).toBe('skimage_brick_512');
  await clickWidget(page, 'gallery.4');
  const fromGallery = JSON.parse(await page.evaluate(() => window.proctex.getParams()));
  const n = (await state(page)).analyses;
  await page.evaluate(() => window.proctex.loadSample('skimage_brick_512.png'));
  await waitAnalyses(page, n + 1);
  expect(core(JSON.parse(await page.evaluate(() => window.proctex.getParams())))).toEqual(core(fromGallery));
});

test('export → import is lossless for every gallery preset (params JSON and preset library)', async ({ page }) => {
  const fs = require('fs');
  await openApp(page);
  await page.waitForFunction(() => {
    window.proctex.requestRepaint();
    return window.proctex.galleryReady && window.proctex.state().gallery.length === 6;
  }, null, { polling: 200, timeout: 120_000 });
  await waitFrames(page, 2);
  const downloadOf = async (widget) => {
    const d = page.waitForEvent('download');
    await clickWidget(page, widget);
    return fs.readFileSync(await (await d).path(), 'utf8');
  };
  for (let i = 0; i < 6; i++) {
    // Load gallery preset i, download its params JSON with the app's button, load another
    // preset, then drop the downloaded file back: the params come back to the byte.
    await clickWidget(page, `gallery.${i}`);
    const before = await page.evaluate(() => window.proctex.getParams());
    const text = await downloadOf('params.download');
    expect(JSON.parse(text)).toEqual(JSON.parse(before));
    await clickWidget(page, `gallery.${(i + 1) % 6}`);
    expect(await page.evaluate(() => window.proctex.getParams())).not.toBe(before);
    await page.evaluate((j) => {
      const dt = new DataTransfer();
      dt.items.add(new File([j], 'texture.json', { type: 'application/json' }));
      document.getElementById('proctex_canvas').dispatchEvent(
        new DragEvent('drop', { dataTransfer: dt, bubbles: true, cancelable: true }));
    }, text);
    await page.waitForFunction((b) => {
      window.proctex.requestRepaint();
      return window.proctex.getParams() === b;
    }, before, { polling: 100, timeout: 30_000 });
  }
  // The whole gallery into presets, the library exported and imported back: the imported
  // copies equal the originals.
  await clickWidget(page, 'gallery.add');
  const library = await downloadOf('presets.export');
  const chooser = page.waitForEvent('filechooser');
  await clickWidget(page, 'presets.import');
  const tmp = require('path').join(require('os').tmpdir(), `proctex-library-${process.pid}.json`);
  fs.writeFileSync(tmp, library);
  await (await chooser).setFiles(tmp);
  await page.waitForFunction(() => {
    window.proctex.requestRepaint();
    return window.proctex.state().presets.length === 12;
  }, null, { polling: 100, timeout: 30_000 });
  const presets = JSON.parse(await page.evaluate(() => window.proctex.getPresets())).presets;
  for (let i = 0; i < 6; i++) expect(presets[6 + i]).toEqual(presets[i]);
});
