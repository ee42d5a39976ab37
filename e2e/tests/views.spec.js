// Views: sphere and cube with orbit controls, the split view against the photo crop, the
// tile-period outline, and the plots.
const { test } = require('@playwright/test');
const {
  expect, openApp, state, waitFrames, drag, grab, channelStats, clickWidget, innerSquare,
} = require('./helpers');

for (const shape of ['sphere', 'cube']) {
  test(`the solid view renders on the ${shape} and orbits with the mouse`, async ({ page }) => {
    await openApp(page);
    await clickWidget(page, `mode.${shape}`);
    await waitFrames(page, 3);
    const s0 = await state(page);
    expect(s0.view_mode).toBe(shape);
    const [x, y, w, h] = s0.widgets.texture;
    // Centre: the textured, lit object; the bottom-left corner (clear of the texture source
    // row at the top-left): the background.
    const centre = await grab(page, innerSquare(s0.widgets.texture, 120));
    for (const c of channelStats(centre)) expect(c.sd).toBeGreaterThan(4);
    const corner = channelStats(await grab(page, [Math.ceil(x) + 2, Math.floor(y + h) - 22, 20, 20]));
    for (const c of corner) expect(Math.abs(c.mean - 28)).toBeLessThan(3);
    // Orbit: drag turns the object, the wheel moves the camera.
    await drag(page, [x + w / 2, y + h / 2], [x + w / 2 + 120, y + h / 2 + 40]);
    await page.mouse.wheel(0, 300);
    await waitFrames(page, 5);
    const s1 = await state(page);
    expect(s1.orbit[0]).not.toBeCloseTo(s0.orbit[0], 0);
    expect(s1.orbit[1]).not.toBeCloseTo(s0.orbit[1], 0);
    expect(s1.orbit[2]).toBeGreaterThan(s0.orbit[2]);
    const turned = await grab(page, innerSquare(s0.widgets.texture, 120));
    expect(Buffer.compare(turned.data, centre.data)).not.toBe(0);
  });
}

test('the split view shows the photo crop beside the texture', async ({ page }) => {
  // Two halves, each wide enough for a 200² grab.
  await openApp(page, { view: [464, 288] });
  await clickWidget(page, 'mode.split');
  await waitFrames(page, 3);
  const s = await state(page);
  const photo = channelStats(await grab(page, innerSquare(s.widgets['split.photo'], 200)));
  const tex = channelStats(await grab(page, innerSquare(s.widgets['split.texture'], 200)));
  for (let c = 0; c < 3; c++) {
    expect(photo[c].sd).toBeGreaterThan(8);
    expect(tex[c].sd).toBeGreaterThan(8);
    // Same material: the means agree within 12 code values.
    expect(Math.abs(photo[c].mean - tex[c].mean)).toBeLessThan(12);
  }
});

test('the tile outline draws the period lattice', async ({ page }) => {
  await openApp(page);
  const p = JSON.parse(await page.evaluate(() => window.proctex.getParams()));
  p.transform.scale = 0.02; // period of some hundred pixels
  await page.evaluate((j) => window.proctex.setParams(j), JSON.stringify(p));
  await clickWidget(page, 'period');
  await waitFrames(page, 3);
  const s = await state(page);
  expect(s.period_outline).toBe(true);
  expect(s.period_lines).toBeGreaterThan(2);
});

test('the plots follow the params once an edit settles', async ({ page }) => {
  await openApp(page);
  let s = await state(page);
  // A click away: the toolbar's Plots opens them over the texture.
  expect(s.widgets['plot.spectrum']).toBeFalsy();
  await clickWidget(page, 'plots.toggle');
  s = await state(page);
  expect(s.widgets['plot.spectrum']).toBeTruthy();
  expect(s.widgets['plot.histograms']).toBeTruthy();
  expect(s.plots_current).toBe(true);
  const p = JSON.parse(await page.evaluate(() => window.proctex.getParams()));
  p.colour.contrast = 2.0;
  await page.evaluate((j) => window.proctex.setParams(j), JSON.stringify(p));
  // The worker recomputes the model's statistics for exactly these params.
  await page.waitForFunction(() => {
    window.proctex.requestRepaint();
    return window.proctex.state().plots_current;
  }, null, { polling: 100 });
});
