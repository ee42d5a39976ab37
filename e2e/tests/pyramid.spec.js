// The pyramid view: the Heeger–Bergen raster synthesis of the crop beside the photo crop and
// the procedural texture, computed in the worker with progress and Cancel, again for a new
// photo, and downloadable as a PNG tile.
const { test } = require('@playwright/test');
const fs = require('fs');
const path = require('path');
const {
  expect, openApp, state, waitFrames, grab, channelStats, clickWidget, dropFile, ROOT,
} = require('./helpers');

// Three panes of 192 × 320 CSS px: a 160² grab at the top of each stays clear of the controls
// at the bottom of the synthesis pane (A, B, m, Cancel / Download: 130 px).
const VIEW = [576, 320];

// The 160² square at the top of a pane, centred across it.
function upper(rect) {
  const [x, y, w] = rect;
  return [Math.ceil(x) + Math.floor((w - 160) / 2), Math.ceil(y) + 4, 160, 160];
}

// Waits until the pyramid view has finished `n` syntheses in all.
async function waitSyntheses(page, n) {
  await page.waitForFunction((k) => {
    window.proctex.requestRepaint();
    const p = window.proctex.state().pyramid;
    return p.finished >= k && !p.running;
  }, n, { polling: 100, timeout: 120_000 });
  await waitFrames(page, 3);
}

// The synthesis pane is a texture of the photo's material: it varies like the photo crop, its
// colours agree with the photo's, and it is not the photo's pixels.
async function expectSynthesisOfPhoto(page) {
  const s = await state(page);
  const photo = await grab(page, upper(s.widgets['pyramid.photo']));
  const syn = await grab(page, upper(s.widgets['pyramid.synthesis']));
  const [ps, ss] = [channelStats(photo), channelStats(syn)];
  for (let c = 0; c < 3; c++) {
    expect(ss[c].sd).toBeGreaterThan(0.4 * ps[c].sd);
    expect(Math.abs(ss[c].mean - ps[c].mean)).toBeLessThan(12);
  }
  expect(Buffer.compare(photo.data, syn.data)).not.toBe(0);
  return s;
}

test('the pyramid view synthesises the sample, and a dropped photo again', async ({ page }) => {
  await openApp(page, { view: VIEW });
  await clickWidget(page, 'mode.pyramid');
  await waitSyntheses(page, 1);
  let s = await expectSynthesisOfPhoto(page);
  expect(s.view_mode).toBe('pyramid');
  expect(s.pyramid.of[0]).toBe(s.photo);
  expect(s.pyramid.size[0]).toBeGreaterThanOrEqual(256);
  console.log(`pyramid synthesis of ${s.photo} (${s.pyramid.size}) in ${s.pyramid.ms.toFixed(0)} ms`);
  // A photo the app does not ship, dropped on the page: its crop is synthesised in turn.
  const dev = path.join(ROOT, '..', 'shared', 'photos', 'dev', 'megaglest_crackedearth_256.png');
  const photo = fs.existsSync(dev) ? dev : path.join(ROOT, 'www', 'samples', 'skimage_gravel_512.png');
  const name = path.basename(photo);
  await dropFile(page, photo, 'drop');
  await waitSyntheses(page, 2);
  s = await expectSynthesisOfPhoto(page);
  expect(s.pyramid.of[0]).toBe(name);
  // Download PNG: the synthesis at its own size.
  const download = page.waitForEvent('download');
  await clickWidget(page, 'pyramid.download');
  const file = await download;
  const stem = name.replace(/\.png$/, '');
  expect(file.suggestedFilename()).toBe(`${stem}_heeger_bergen_${s.pyramid.size[0]}x${s.pyramid.size[1]}.png`);
  const png = await page.evaluate(() => window.proctex.lastPng);
  expect([png.width, png.height]).toEqual(s.pyramid.size);
  expect(png.bytes).toBeGreaterThan(1000);
});

test('Cancel stops the pyramid synthesis, and it can run again', async ({ page }) => {
  await openApp(page, { view: VIEW });
  // Rounds slowed down so that Cancel lands between them: on a fast machine the whole
  // synthesis could otherwise end before the click.
  await page.evaluate(() => window.proctex.setSynthesisRoundDelay(250));
  await clickWidget(page, 'mode.pyramid');
  // Cancel as soon as the first rounds are reported.
  await page.waitForFunction(() => {
    window.proctex.requestRepaint();
    const p = window.proctex.state().pyramid;
    return p.running && p.progress !== null;
  }, null, { polling: 20, timeout: 60_000 });
  await clickWidget(page, 'pyramid.cancel');
  await page.waitForFunction(() => {
    window.proctex.requestRepaint();
    return !window.proctex.state().pyramid.running;
  }, null, { polling: 50, timeout: 30_000 });
  await waitFrames(page, 2);
  let s = await state(page);
  expect(s.pyramid.cancelled).toBe(true);
  expect(s.pyramid.finished).toBe(0);
  expect(s.pyramid.size).toBeNull();
  // Nothing starts by itself for the crop it was told to stop; the button starts it again.
  await page.waitForTimeout(500);
  s = await state(page);
  expect(s.pyramid.running).toBe(false);
  await page.evaluate(() => window.proctex.setSynthesisRoundDelay(0));
  await clickWidget(page, 'pyramid.again');
  await waitSyntheses(page, 1);
  await expectSynthesisOfPhoto(page);
});

test('the mixture slider at 0 and 1 gives the two syntheses; A and B come from anywhere', async ({ page }) => {
  await openApp(page, { view: VIEW });
  await clickWidget(page, 'mode.pyramid');
  await waitSyntheses(page, 1);
  let s = await state(page);
  const own = s.pyramid.checksum;
  expect(s.widgets['pyramid.mix']).toBeTruthy(); // B ("mix with"), over the synthesis
  const gravel = 'sample:skimage_gravel_512.png';
  const mixAt = async (m, n) => {
    await page.evaluate(([src, t]) => window.proctex.setPyramidMix(src, t), [gravel, m]);
    await waitSyntheses(page, n);
    const p = (await state(page)).pyramid;
    expect(p.mix).toEqual([gravel, m]);
    return p.checksum;
  };
  expect(await mixAt(0, 2)).toBe(own);
  const towardsGravel = await mixAt(1, 3);
  const halfway = await mixAt(0.5, 4);
  expect(halfway).not.toBe(own);
  expect(halfway).not.toBe(towardsGravel);
  s = await state(page);
  expect(s.widgets['pyramid.m']).toBeTruthy();
  await expectSynthesisOfPhotoColours(page, 30);
  // m = 1 is the gravel sample's own synthesis, picked as A (both photos are 512²: the same
  // size).
  await page.evaluate(() => window.proctex.setPyramidMix(null, 0, 'sample:skimage_gravel_512.png'));
  await waitSyntheses(page, 5);
  s = await state(page);
  expect(s.pyramid.a).toBe('sample:skimage_gravel_512.png');
  expect(s.pyramid.mix).toBeNull();
  expect(s.pyramid.checksum).toBe(towardsGravel);
  // A as well as B from the samples: A = gravel at m = 0 is gravel's synthesis again.
  await page.evaluate(() => window.proctex.setPyramidMix(
    'sample:skimage_brick_512.png', 0, 'sample:skimage_gravel_512.png'));
  await waitSyntheses(page, 6);
  expect((await state(page)).pyramid.checksum).toBe(towardsGravel);
  expect((await state(page)).widgets['pyramid.a']).toBeTruthy();
  // And the crop as B: A = gravel, B = the crop at m = 1 is the crop's own synthesis.
  await page.evaluate(() => window.proctex.setPyramidMix('crop', 1, 'sample:skimage_gravel_512.png'));
  await waitSyntheses(page, 7);
  s = await state(page);
  expect(s.pyramid.mix).toEqual(['crop', 1]);
  expect(s.pyramid.checksum).toBe(own);
  // A gallery texture (the gravel sample's analysis, rendered at 256²) as A.
  await page.waitForFunction(() => window.proctex.galleryReady, null, { timeout: 120_000 });
  await page.evaluate(() => window.proctex.setPyramidMix(null, 0, 'gallery:skimage_gravel_512'));
  await waitSyntheses(page, 8);
  s = await state(page);
  expect(s.pyramid.a).toBe('gallery:skimage_gravel_512');
  expect(s.pyramid.error).toBeNull();
  expect(s.pyramid.size).toEqual([256, 256]);
  await expectSynthesisOfPhotoColours(page, 30);
});

// The synthesis pane is a real texture (it varies), whatever it mixes.
async function expectSynthesisOfPhotoColours(page, minSd) {
  const s = await state(page);
  const syn = channelStats(await grab(page, upper(s.widgets['pyramid.synthesis'])));
  const sd = syn.reduce((a, c) => a + c.sd, 0) / 3;
  expect(sd).toBeGreaterThan(minSd / 10);
}
