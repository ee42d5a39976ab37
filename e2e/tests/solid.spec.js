// The solid views' Heeger–Bergen source: the crop's raster volume (an n³ solid texture made in
// the worker, with progress and Cancel) drawn on the sphere and the cube from a 3D texture.
const { test } = require('@playwright/test');
const {
  expect, openApp, state, waitFrames, grab, channelStats, clickWidget, innerSquare, waitAnalyses,
} = require('./helpers');

// Waits until the solid views have received `n` volumes in all.
async function waitVolumes(page, n) {
  await page.waitForFunction((k) => {
    window.proctex.requestRepaint();
    const v = window.proctex.state().solid;
    return v.finished >= k && !v.running;
  }, n, { polling: 100, timeout: 180_000 });
  await waitFrames(page, 3);
}

// The object in the middle of the view (clear of the source controls at its top-left).
async function centre(page) {
  const s = await state(page);
  return grab(page, innerSquare(s.widgets.texture, 120));
}

test('the Heeger–Bergen volume renders on the sphere and the cube', async ({ page }) => {
  await openApp(page);
  await clickWidget(page, 'mode.sphere');
  await waitFrames(page, 3);
  const procedural = await centre(page);
  let s = await state(page);
  expect(s.solid.source).toBe('procedural');
  expect(s.solid.finished).toBe(0); // nothing is synthesised until it is asked for
  await clickWidget(page, 'solid.raster');
  await waitVolumes(page, 1);
  s = await state(page);
  expect(s.solid.source).toBe('heeger-bergen');
  expect(s.solid.n).toBe(64);
  expect(s.solid.of[0]).toBe(s.photo);
  // A voxel stands for crop / 128 photo pixels.
  expect(s.solid.voxels_per_unit).toBeCloseTo(128 / Math.max(s.solid.of[1][2], s.solid.of[1][3]), 4);
  console.log(`64³ volume of ${s.photo} in ${s.solid.ms.toFixed(0)} ms`);
  // The sphere shows the volume: textured, lit, of the material's colours (the procedural
  // sphere's, within 20 code values), and not the procedural texture's pixels.
  const raster = await centre(page);
  const [rs, ps] = [channelStats(raster), channelStats(procedural)];
  for (let c = 0; c < 3; c++) {
    expect(rs[c].sd).toBeGreaterThan(4);
    expect(Math.abs(rs[c].mean - ps[c].mean)).toBeLessThan(20);
  }
  expect(Buffer.compare(raster.data, procedural.data)).not.toBe(0);
  // The cube shows the same volume, without synthesising it again.
  await clickWidget(page, 'mode.cube');
  await waitFrames(page, 3);
  const cube = await centre(page);
  for (const c of channelStats(cube)) expect(c.sd).toBeGreaterThan(4);
  expect(Buffer.compare(cube.data, raster.data)).not.toBe(0);
  expect((await state(page)).solid.finished).toBe(1);
  // Back to the procedural texture: the procedural sphere again.
  await clickWidget(page, 'mode.sphere');
  await clickWidget(page, 'solid.procedural');
  await waitFrames(page, 3);
  expect(Buffer.compare((await centre(page)).data, procedural.data)).toBe(0);
});

test('a new photo gets its own volume; Cancel stops it and it can run again', async ({ page }) => {
  await openApp(page);
  await clickWidget(page, 'mode.sphere');
  await page.evaluate(() => window.proctex.setSolidSource('heeger-bergen', 64));
  await waitVolumes(page, 1);
  const first = (await state(page)).solid.checksum;
  // A new photo starts a new volume; cancel it as soon as rounds are reported.
  const before = (await state(page)).analyses;
  await page.evaluate(() => window.proctex.loadSample('skimage_gravel_512.png'));
  await waitAnalyses(page, before + 1);
  await page.waitForFunction(() => {
    window.proctex.requestRepaint();
    const v = window.proctex.state().solid;
    return v.running && v.progress !== null;
  }, null, { polling: 20, timeout: 60_000 });
  await clickWidget(page, 'solid.cancel');
  await page.waitForFunction(() => {
    window.proctex.requestRepaint();
    return !window.proctex.state().solid.running;
  }, null, { polling: 50, timeout: 30_000 });
  await waitFrames(page, 2);
  let s = await state(page);
  expect(s.solid.cancelled).toBe(true);
  expect(s.solid.finished).toBe(1);
  expect(s.solid.n).toBeNull(); // the old photo's volume is not shown for the new one
  await page.waitForTimeout(500);
  expect((await state(page)).solid.running).toBe(false);
  await clickWidget(page, 'solid.again');
  await waitVolumes(page, 2);
  s = await state(page);
  expect(s.solid.of[0]).toBe('skimage_gravel_512.png');
  expect(s.solid.checksum).not.toBe(first);
  for (const c of channelStats(await centre(page))) expect(c.sd).toBeGreaterThan(4);
});
