// The browser app in Debian Chromium with SwiftShader WebGPU.
const { test } = require('@playwright/test');
const fs = require('fs');
const path = require('path');
const { expect, openApp, state, waitFrames, drag, grab, highFrequencyEnergy, gradientEnergy, channelStats, cliRender, innerSquare, reveal, clickWidget, ROOT, dropFile } = require('./helpers');

test('opens on the sample, already rendered', async ({ page }) => {
  await openApp(page);
  const s = await state(page);
  expect(s.photo).toBe('stk_rock_mountain_512.png');
  expect(s.error).toBeNull();
  expect(s.analysis_ms).toBeGreaterThan(0);
  // The sample's model suggestions wait for the user's click (suggest.spec.js clicks it).
  expect(s.widgets['suggest.start']).toBeTruthy();
  expect(s.suggest_progress).toBeNull();
  expect(s.suggestions).toEqual([]);
  const img = await grab(page, innerSquare(s.widgets.texture, 256));
  const stats = channelStats(img);
  // A real texture: varied, and with the photo's greyish colour.
  for (const c of stats) {
    expect(c.sd).toBeGreaterThan(8);
    expect(c.mean).toBeGreaterThan(100);
    expect(c.mean).toBeLessThan(200);
  }
});

// The GPU view of the current params over a fixed view against the CLI's CPU render of the
// same pixels: the mean and largest absolute difference per channel (of 255).
async function gpuVsCpu(page) {
  // Fixed view: world origin (37.25, -11.5) at the view's top-left, 1.5 world units per pixel.
  const origin = [37.25, -11.5], unitsPerPoint = 1.5;
  await page.evaluate(([o, u]) => window.proctex.setView(o[0], o[1], u), [origin, unitsPerPoint]);
  await waitFrames(page, 3);
  const s = await state(page);
  const [vx, vy] = s.widgets.texture;
  const size = 256;
  // The view's first whole pixel column/row and the world point at its top-left corner.
  const px = Math.ceil(vx) + 8, py = Math.ceil(vy) + 8;
  const gpu = await grab(page, [px, py, size, size]);
  const frameX = Math.round(vx), frameY = Math.round(vy);
  const cpu = cliRender(await page.evaluate(() => window.proctex.getParams()), {
    width: size, height: size, pixelSize: unitsPerPoint,
    origin: [origin[0] + (px - frameX) * unitsPerPoint, origin[1] + (py - frameY) * unitsPerPoint],
  });
  let sum = 0, max = 0;
  for (let i = 0; i < size * size; i++) {
    for (let c = 0; c < 3; c++) {
      const d = Math.abs(gpu.data[i * 4 + c] - cpu.data[i * 4 + c]);
      sum += d; max = Math.max(max, d);
    }
  }
  return { mae: sum / (size * size * 3), max, size, gpu };
}

test('GPU view equals the CPU reference renderer', async ({ page }) => {
  await openApp(page);
  const { mae, max, size } = await gpuVsCpu(page);
  console.log(`GPU vs CPU over ${size}×${size}: mean |diff| = ${mae.toFixed(4)}/255, max ${max}/255`);
  expect(mae).toBeLessThan(0.5);
});

test('GPU view equals the CPU reference renderer for every pattern family', async ({ page }) => {
  // Twelve SwiftShader renders and CLI renders: ~1.8 min alone, past 3 min on a busy machine.
  test.setTimeout(360_000);
  const { execFileSync } = require('child_process');
  const os = require('os');
  await openApp(page);
  // The brick sample fitted with the brick family (ramp, residual, tone curve), its pattern
  // then swapped for each family at its defaults, plus the values at the top of the ranges
  // that only step 6 of the fit or the sliders reach (ridged's roughness 1, planks' widths,
  // cells' jitter 0), and cells' staggered, warped lattice (scales).
  const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'proctex-families-'));
  execFileSync(path.join(ROOT, 'target', 'release', 'proctex'), ['analyze',
    path.join(ROOT, 'www', 'samples', 'skimage_brick_512.png'), '--model', 'brick', '--refine', '0',
    '-o', path.join(dir, 'p.json')]);
  const fitted = JSON.parse(fs.readFileSync(path.join(dir, 'p.json'), 'utf8'));
  const cases = [
    ['perlin', {}], ['turbulence', {}], ['ridged', {}], ['ridged', { roughness: 1.0 }], ['grid', {}],
    ['brick', {}], ['cells', {}], ['cells', { jitter: 0, stagger: 1, warp: 0.5 }], ['planks', {}],
    ['planks', { widths: 1, length: 6 }],
    ['wood_lines', {}], ['rings', { centre_x: 2, centre_y: 1.5 }],
  ];
  for (const [kind, values] of cases) {
    const p = JSON.parse(JSON.stringify(fitted));
    p.model.pattern.kind = kind;
    p.model.pattern.values = values;
    p.model.pattern.scale = 24;
    await page.evaluate((j) => window.proctex.setParams(j), JSON.stringify(p));
    await waitFrames(page, 3);
    const got = JSON.parse(await page.evaluate(() => window.proctex.getParams())).model.pattern;
    expect(got.kind).toBe(kind);
    for (const [k, v] of Object.entries(values)) expect(got.values[k]).toBeCloseTo(v, 5);
    const { mae, max, size, gpu } = await gpuVsCpu(page);
    const sd = channelStats(gpu).map((c) => c.sd);
    console.log(`GPU vs CPU, ${kind} ${JSON.stringify(values)}, ${size}×${size}: mean |diff| = ${mae.toFixed(4)}/255, max ${max}/255; sd ${sd.map((v) => v.toFixed(1)).join(' ')}`);
    expect(mae).toBeLessThan(0.5);
    // A pattern, not a flat field (both renderers agreeing on nothing).
    expect(Math.max(...sd)).toBeGreaterThan(4);
  }
  fs.rmSync(dir, { recursive: true, force: true });
});

test('dragging the finest band raises and removes high-frequency energy', async ({ page }) => {
  await openApp(page);
  const before = await state(page);
  const square = innerSquare(before.widgets.texture, 256);
  const energy0 = highFrequencyEnergy(await grab(page, square));
  // The analysis draws the finest band after the histogram (its weight in the sum is 0): its
  // slider is the first channel's part after it.
  const [x, y, w, h] = await reveal(page, 'fine.0');
  // The slider's rail is the left part of the widget (the value box and label follow it).
  const railLeft = x + 2, railRight = x + 100 - 2, cy = y + h / 2;
  const knob = async () => {
    const p = JSON.parse(await page.evaluate(() => window.proctex.getParams()));
    return (p.model.fine || [0, 0, 0])[0];
  };
  const w0 = await knob();
  expect(w0).toBeGreaterThan(0);
  await drag(page, [railLeft + 20, cy], [railRight, cy], 8);
  await waitFrames(page, 3);
  const wHigh = await knob();
  expect(wHigh).toBeGreaterThan(w0 * 1.5);
  const energyHigh = highFrequencyEnergy(await grab(page, square));
  await drag(page, [railLeft + 40, cy], [railLeft - 40, cy], 8);
  await waitFrames(page, 3);
  expect(await knob()).toBe(0);
  const energyZero = highFrequencyEnergy(await grab(page, square));
  console.log(`high-frequency energy: analysed ${energy0.toFixed(1)}, raised ${energyHigh.toFixed(1)}, zero ${energyZero.toFixed(1)}`);
  expect(energyHigh).toBeGreaterThan(energy0 * 1.3);
  expect(energyZero).toBeLessThan(energy0 * 0.8);
  // One undo step per drag.
  expect((await state(page)).undo).toBe(2);
});

test('band orientations turn the streaks, and their sliders edit them', async ({ page }) => {
  await openApp(page);
  const square = innerSquare((await state(page)).widgets.texture, 256);
  const base = JSON.parse(await page.evaluate(() => window.proctex.getParams()));
  const bands = base.model.weights[0].length;
  // Every band at full strength: streaks along the texel x axis (0°), then the y axis (90°).
  const ratio = async (angle) => {
    const p = structuredClone(base);
    p.model.orientation = Array.from({ length: bands }, () => ({ angle_deg: angle, strength: 1 }));
    await page.evaluate((j) => window.proctex.setParams(j), JSON.stringify(p));
    await waitFrames(page, 3);
    const [xx, yy] = gradientEnergy(await grab(page, square));
    return yy / xx;
  };
  const along = await ratio(0), across = await ratio(90);
  console.log(`gradient energy y/x: streaks at 0° ${along.toFixed(2)}, at 90° ${across.toFixed(2)}`);
  // A pure derivative band has 3× the gradient energy across its streaks as along them.
  expect(along).toBeGreaterThan(1.5);
  expect(across).toBeLessThan(1 / 1.5);
  // The strength slider of band 1: dragged to its left end, that band is isotropic.
  const [x, y, , h] = await reveal(page, 'orient.strength.1');
  const cy = y + h / 2;
  await drag(page, [x + 40, cy], [x - 60, cy], 8);
  await waitFrames(page, 3);
  const after = JSON.parse(await page.evaluate(() => window.proctex.getParams()));
  expect(after.model.orientation[1].strength).toBe(0);
  expect(after.model.orientation[2].strength).toBe(1);
});

test("the noise model's output tone curve recolours the texture and its checkbox turns it off", async ({ page }) => {
  await openApp(page);
  const square = innerSquare((await state(page)).widgets.texture, 256);
  const base = JSON.parse(await page.evaluate(() => window.proctex.getParams()));
  expect(base.model.kind).toBe('noise');
  const plain = structuredClone(base);
  delete plain.model.tone;
  await page.evaluate((j) => window.proctex.setParams(j), JSON.stringify(plain));
  await waitFrames(page, 3);
  const before = channelStats(await grab(page, square));
  // A curve that maps every red value to 0.9 and leaves green and blue alone (the identity).
  const p = structuredClone(plain);
  const identity = [0, 0.25, 0.5, 0.75, 1];
  p.model.tone = { enabled: true, range: [[0, 1], [0, 1], [0, 1]], knots: [identity.map(() => 0.9), identity, identity] };
  await page.evaluate((j) => window.proctex.setParams(j), JSON.stringify(p));
  await waitFrames(page, 3);
  const toned = channelStats(await grab(page, square));
  // 0.9 is 230 in 8 bits (sRGB-encoded output, as the photo).
  expect(Math.abs(toned[0].mean - 229.5)).toBeLessThan(2);
  expect(toned[0].sd).toBeLessThan(1);
  expect(Math.abs(toned[1].mean - before[1].mean)).toBeLessThan(1);
  await reveal(page, 'tone');
  await clickWidget(page, 'tone');
  await waitFrames(page, 3);
  const after = JSON.parse(await page.evaluate(() => window.proctex.getParams()));
  expect(after.model.tone.enabled).toBe(false);
  const off = channelStats(await grab(page, square));
  expect(Math.abs(off[0].mean - before[0].mean)).toBeLessThan(1);
});

test('wheel zooms and drag pans the view', async ({ page }) => {
  await openApp(page);
  const s0 = await state(page);
  const [x, y, w, h] = s0.widgets.texture;
  const cx = x + w / 2, cy = y + h / 2;
  await page.mouse.move(cx, cy);
  await page.mouse.wheel(0, 400); // scroll down: zoom out
  await waitFrames(page, 10);
  const s1 = await state(page);
  expect(s1.view_units_per_point).toBeGreaterThan(s0.view_units_per_point * 1.2);
  await drag(page, [cx, cy], [cx - 100, cy - 50], 5);
  await waitFrames(page, 3);
  const s2 = await state(page);
  expect(s2.view_origin[0]).toBeCloseTo(s1.view_origin[0] + 100 * s1.view_units_per_point, 0);
  expect(s2.view_origin[1]).toBeCloseTo(s1.view_origin[1] + 50 * s1.view_units_per_point, 0);
});

test('a corrupt file and a text file dropped on the page give a visible error and keep the texture', async ({ page }) => {
  await openApp(page);
  const params = await page.evaluate(() => window.proctex.getParams());
  for (const file of ['truncated.png', 'text.png']) {
    const bytes = [...fs.readFileSync(path.join(ROOT, 'analyzer', 'tests', 'bad', file))];
    await page.evaluate(([b, n]) => {
      const dt = new DataTransfer();
      dt.items.add(new File([new Uint8Array(b)], n, { type: 'image/png' }));
      document.getElementById('proctex_canvas').dispatchEvent(
        new DragEvent('drop', { dataTransfer: dt, bubbles: true, cancelable: true }));
    }, [bytes, file]);
    await page.waitForFunction((n) => {
      window.proctex.requestRepaint();
      const s = window.proctex.state();
      return s.error && s.error.includes(n) && s.widgets.error;
    }, file, { polling: 100 });
    const s = await state(page);
    expect(s.error).toContain('cannot read the image');
    expect(s.photo).toBe('stk_rock_mountain_512.png');
    expect(await page.evaluate(() => window.proctex.getParams())).toBe(params);
  }
  // And it keeps working: the next good photo is analysed.
  const n = (await state(page)).analyses;
  await page.evaluate(() => window.proctex.loadSample('skimage_grass_512.png'));
  await page.waitForFunction((k) => window.proctex.state().analyses > k, n);
  expect((await state(page)).error).toBeNull();
});

test('dropping a photo changes the params and the image, and the colours follow the photo', async ({ page }) => {
  await openApp(page);
  const before = await page.evaluate(() => window.proctex.getParams());
  const photo = path.join(ROOT, '..', 'shared', 'photos', 'skimage_grass_512.png');
  const fallback = path.join(ROOT, 'www', 'samples', 'skimage_grass_512.png');
  await dropFile(page, fs.existsSync(photo) ? photo : fallback, 'drop');
  const after = JSON.parse(await page.evaluate(() => window.proctex.getParams()));
  expect(JSON.stringify(after)).not.toBe(before);
  // The rendered view's mean colour follows the grass photo's mean (within 10 code values).
  const s = await state(page);
  const img = await grab(page, innerSquare(s.widgets.texture, 256));
  const stats = channelStats(img);
  for (let c = 0; c < 3; c++) {
    expect(Math.abs(stats[c].mean - 255 * after.colour.mean[c])).toBeLessThan(10);
  }
});

test('pasting an image from the clipboard analyses it', async ({ page }) => {
  await openApp(page);
  await dropFile(page, path.join(ROOT, 'www', 'samples', 'stk_blackrock_256.png'), 'paste');
  expect((await state(page)).error).toBeNull();
});

test('showing the controls edits nothing: a value outside its slider\'s range stays as it is', async ({ page }) => {
  // egui's sliders clamp to their range whenever drawn unless told not to, and its colour button
  // writes back its HSVA round trip: either changed params that nobody touched (an undo step;
  // the list's best model then not adopted over an "edit").
  await openApp(page);
  const p = JSON.parse(await page.evaluate(() => window.proctex.getParams()));
  p.transform.scale = 120; // the view's slider stops at 50
  p.colour.mean = [0.6308582, 0.5563771, 0.41046908]; // a colour egui's HSVA round trip moves
  await page.evaluate((j) => window.proctex.setParams(j), JSON.stringify(p));
  await waitFrames(page, 5);
  const shown = JSON.parse(await page.evaluate(() => window.proctex.getParams()));
  expect(shown.transform.scale).toBe(120);
  expect(shown.colour.mean).toEqual(p.colour.mean);
  const { widgets } = await state(page);
  expect(widgets.scale && widgets.mean).toBeTruthy(); // both drawn
});
