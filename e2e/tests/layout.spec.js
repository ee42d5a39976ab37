// The first screen reads in the order of the work: the photo and its crop, the model
// suggestions, the texture, the parameters, and the export strip, all in view without scrolling
// at the two window sizes a laptop user has (screenshots kept in test-results/ for review).
const path = require('path');
const { test } = require('@playwright/test');
const { expect, openApp, state } = require('./helpers');

for (const [width, height] of [[1280, 800], [1100, 720]]) {
  test(`first screen at ${width}×${height}: photo, suggestions, texture, parameters, export in view`, async ({ page }) => {
    await page.setViewportSize({ width, height });
    await openApp(page, { view: null });
    const s = await state(page);
    const inView = (name) => {
      const r = s.widgets[name];
      expect(r, `widget ${name}`).toBeTruthy();
      const [x, y, w, h] = r;
      expect(x >= 0 && y >= 0 && x + w <= width && y + h <= height, `${name} ${JSON.stringify(r)} in ${width}×${height}`).toBe(true);
      return r;
    };
    const photo = inView('photo');
    // The start-up sample's suggestions wait for this button.
    const suggest = inView('suggest.start');
    const texture = inView('texture');
    const firstSlider = inView('weight.0.0');
    for (const name of ['params.download', 'params.link', 'export.copy_wgsl', 'export.copy_glsl', 'export.png']) {
      inView(name);
    }
    // Left to right and top to bottom: photo above the suggestions, both left of the texture,
    // the parameters right of it.
    expect(photo[1]).toBeLessThan(suggest[1]);
    expect(photo[0] + photo[2]).toBeLessThanOrEqual(texture[0] + 1);
    expect(texture[0] + texture[2]).toBeLessThanOrEqual(firstSlider[0] + 1);
    await page.screenshot({ path: path.join(__dirname, '..', 'test-results', `first-screen-${width}x${height}.png`) });
  });
}
