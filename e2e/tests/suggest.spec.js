// The automatic model choice in the app: after each analysis the worker retrieves and
// refines every structured model family, the app lists them ranked with thumbnails and scores
// (the best family fitted with the list, the other rows' fits following it),
// adopts the best, and a click adopts another.
const { test } = require('@playwright/test');
const { execFileSync } = require('child_process');
const fs = require('fs');
const path = require('path');
const {
  expect, openApp, state, waitFrames, drag, grab, innerSquare, reveal, clickWidget, suggestionsFor, suggestionsForFile,
  suggestionsAfter, tmpFile, CLI, ROOT,
} = require('./helpers');

const patternOf = (json) => {
  const p = JSON.parse(json);
  return p.model.kind === 'structured' ? p.model.pattern.kind : 'noise';
};

// Mean absolute difference of the red channel of two grabs of the same rectangle.
function meanDiff(a, b) {
  let diff = 0;
  for (let i = 0; i < a.data.length; i += 4) diff += Math.abs(a.data[i] - b.data[i]);
  return diff / (a.data.length / 4);
}

// `a` and `b` have the same structure and values within 1e-4 (relative, or absolute near 0).
function expectClose(a, b, where) {
  if (typeof a === 'number' && typeof b === 'number') {
    expect(Math.abs(a - b), `${where}: ${a} vs ${b}`).toBeLessThanOrEqual(1e-4 * Math.max(1, Math.abs(b)));
  } else if (a && b && typeof a === 'object' && typeof b === 'object') {
    expect(Object.keys(a).sort(), where).toEqual(Object.keys(b).sort());
    for (const k of Object.keys(a)) expectClose(a[k], b[k], `${where}.${k}`);
  } else {
    expect(a, where).toEqual(b);
  }
}

// Waits until row `i` of the list is the adopted model.
async function waitAdopted(page, i) {
  await page.waitForFunction((k) => {
    window.proctex.requestRepaint();
    return window.proctex.state().adopted === k;
  }, i, { polling: 100, timeout: 60_000 });
  await waitFrames(page, 3);
}

async function adopt(page, i) {
  const before = await state(page);
  await clickWidget(page, `suggestion.${i}`);
  await waitAdopted(page, i);
  expect((await state(page)).undo).toBe(before.undo + 1);
}

test('a brick photo ranks a brick-like model first and adopts it; a click adopts another', async ({ page }) => {
  await openApp(page);
  const s = await suggestionsFor(page, 'skimage_brick_512.png');
  expect(['brick', 'planks', 'grid']).toContain(s.suggestions[0].name);
  expect(s.suggestions.map((r) => r.name)).toContain('noise');
  expect(s.suggestions.length).toBe(10);
  // The list came with the families that order it fitted; every other row's fit (texture
  // distance, thumbnail) followed it into the app.
  expect(s.suggestions.every((r) => typeof r.distance === 'number')).toBe(true);
  expect(s.adopted).toBe(0);
  expect(s.error).toBeNull();
  expect(patternOf(await page.evaluate(() => window.proctex.getParams()))).toBe(s.suggestions[0].name);
  // The adopted model's final fit ran in tasks, shared with the helper workers when there are
  // any, and is the CLI's analysis of the same photo (up to the last digits: wasm's maths
  // functions are not the native ones).
  const t = await page.evaluate(() => window.proctex.lastSuggestions());
  expect(t.fitTasks).toBeGreaterThan(1);
  if (t.helpers > 0) expect(t.fitHelped).toBeGreaterThan(0);
  // So did the fits of the classifier's first three families, whose renders order the list
  // (this worker fitted the noise model meanwhile; the sample is like the classifier's training
  // textures, so no fourth family joins them).
  expect(t.orderTasks).toBe(3);
  if (t.helpers > 0) expect(t.orderHelped).toBeGreaterThan(0);
  const cli = JSON.parse(execFileSync(CLI, ['analyze', path.join(ROOT, 'www', 'samples', 'skimage_brick_512.png'),
    '--json'], { stdio: ['ignore', 'pipe', 'ignore'] }).toString());
  expectClose(JSON.parse(await page.evaluate(() => window.proctex.getParams())).model, cli.model, 'model');

  const square = innerSquare(s.widgets.texture, 192);
  const first = await grab(page, square);
  // Adopt the noise model, then another pattern family: the params and the image follow.
  const noise = s.suggestions.findIndex((r) => r.name === 'noise');
  await adopt(page, noise);
  expect(patternOf(await page.evaluate(() => window.proctex.getParams()))).toBe('noise');
  const other = s.suggestions.findIndex((r, i) => i > 0 && r.name !== 'noise');
  await adopt(page, other);
  const name = s.suggestions[other].name;
  expect(patternOf(await page.evaluate(() => window.proctex.getParams()))).toBe(name);
  expect(meanDiff(await grab(page, square), first)).toBeGreaterThan(2);
  // The pick's final fit also ran in tasks shared with the helpers, and is the CLI's analysis
  // of the photo with that family.
  const a = await page.evaluate(() => window.proctex.lastAdoption());
  console.log(`adopted ${name} (row ${other}): its final fit ${a.ms.toFixed(0)} ms, ` +
    `${a.fitHelped} of ${a.fitTasks} tasks run by ${a.helpers} helper workers`);
  expect(a.index).toBe(other);
  expect(a.fitTasks).toBeGreaterThan(1);
  if (a.helpers > 0) expect(a.fitHelped).toBeGreaterThan(0);
  const picked = JSON.parse(execFileSync(CLI, ['analyze', path.join(ROOT, 'www', 'samples', 'skimage_brick_512.png'),
    '--model', name, '--json'], { stdio: ['ignore', 'pipe', 'ignore'] }).toString());
  expectClose(JSON.parse(await page.evaluate(() => window.proctex.getParams())).model, picked.model, 'picked model');

  // A second pick while the first is still being fitted replaces it: only the second is adopted.
  const [p1, p2] = s.suggestions.map((r, i) => i).filter((i) => i > 0 && i !== other && i !== noise);
  const undo = (await state(page)).undo;
  await clickWidget(page, `suggestion.${p1}`);
  await clickWidget(page, `suggestion.${p2}`);
  await waitAdopted(page, p2);
  expect((await state(page)).undo).toBe(undo + 1);
  expect(patternOf(await page.evaluate(() => window.proctex.getParams()))).toBe(s.suggestions[p2].name);
  const last = await page.evaluate(() => window.proctex.lastAdoption());
  expect([last.index, last.count]).toEqual([p2, a.count + 1]);
  // The same when the second pick is the noise model (fitted in one piece, not in tasks).
  await clickWidget(page, `suggestion.${p1}`);
  await clickWidget(page, `suggestion.${noise}`);
  await waitAdopted(page, noise);
  await page.waitForTimeout(6000); // the superseded fit would have landed by now
  await waitFrames(page, 3);
  expect((await state(page)).adopted).toBe(noise);
  expect((await state(page)).undo).toBe(undo + 2);
  expect(patternOf(await page.evaluate(() => window.proctex.getParams()))).toBe('noise');
});

test("the user's pick survives the same crop ranked again; another photo gets its best", async ({ page }) => {
  await openApp(page);
  const s = await suggestionsFor(page, 'skimage_brick_512.png');
  const other = s.suggestions.findIndex((r, i) => i > 0 && r.name !== 'noise');
  const name = s.suggestions[other].name;
  await adopt(page, other);
  // The same photo and crop analysed and ranked again: the picked model is adopted again.
  const again = await suggestionsFor(page, 'skimage_brick_512.png');
  const row = again.suggestions.findIndex((r) => r.name === name);
  expect(row).toBeGreaterThan(0);
  await waitAdopted(page, row);
  expect(patternOf(await page.evaluate(() => window.proctex.getParams()))).toBe(name);
  // Another photo: its own best, and back on the first, the pick is forgotten.
  const gravel = await suggestionsFor(page, 'skimage_gravel_512.png');
  expect(gravel.adopted).toBe(0);
  const third = await suggestionsFor(page, 'skimage_brick_512.png');
  expect(third.adopted).toBe(0);
  expect(patternOf(await page.evaluate(() => window.proctex.getParams()))).toBe(third.suggestions[0].name);
});

test('a gravel photo ranks the noise model first and keeps it', async ({ page }) => {
  await openApp(page);
  const s = await suggestionsFor(page, 'skimage_gravel_512.png');
  expect(s.suggestions[0].name).toBe('noise');
  expect(s.adopted).toBe(0);
  expect(patternOf(await page.evaluate(() => window.proctex.getParams()))).toBe('noise');
  // The noise model led, so the ranking compared the classifier's nearest family's render with
  // it: that family's first round ran before the list in tasks shared with the helper workers,
  // one of which scattered the photo and the noise model's render.
  expectNearerInTasks(await page.evaluate(() => window.proctex.lastSuggestions()));
});

// The nearer-render rule's fit ran in tasks before the list (`t`: `lastSuggestions()`), shared
// with the helper workers where there are any: a helper took some of the round's work, its
// tasks or the two scatterings. Which of the two is scheduling: on a loaded machine the helper
// that scatters can come back after this worker has done every task (0 of 7 helped, scattered
// there), so neither alone is asserted.
function expectNearerInTasks(t) {
  console.log(`the nearer render's first round: ${t.nearer?.ms.toFixed(0)} ms, ${t.nearer?.helped} of ` +
    `${t.nearer?.tasks} tasks by ${t.helpers} helper workers; scattered there: ${t.nearer?.scattered}`);
  expect(t.nearer).not.toBeNull();
  expect(t.nearer.tasks).toBeGreaterThan(1);
  if (t.helpers > 0) {
    expect(t.nearer.helped > 0 || t.nearer.scattered).toBe(true);
  }
}

test("a pebble bed's nearest family comes first by its render, and its fit is the CLI's", async ({ page }) => {
  // A development photo's top-left quadrant (a pebble bed, labelled cells) on which the noise
  // model leads by texture distance but the cells' render is the nearer in the scattering space.
  const file = path.join(ROOT, '..', 'shared', 'photos', 'dev', 'openarena_pebbles_256.png');
  await openApp(page);
  const s = await suggestionsForFile(page, file, 128, 128);
  expect(s.suggestions[0].name).toBe('cells');
  expect(s.adopted).toBe(0);
  const t = await page.evaluate(() => window.proctex.lastSuggestions());
  expectNearerInTasks(t);
  // The adopted fit went on from that first round: the CLI's analysis of the same crop.
  const cli = JSON.parse(execFileSync(CLI, ['analyze', file, '--crop', '0,0,128,128', '--json'],
    { stdio: ['ignore', 'pipe', 'ignore'] }).toString());
  expect(cli.model.pattern.kind).toBe('cells');
  expectClose(JSON.parse(await page.evaluate(() => window.proctex.getParams())).model, cli.model, 'model');
});

test('a first family whose render is speckier than the photo is passed over for the next, as the CLI does', async ({ page }) => {
  // A development photo's top-left quadrant (cracked earth, labelled cells and ridged): the
  // ranking puts ridged first, whose render has more isolated specks than 1.5× the photo's at
  // every fit; cells, second, renders within the limit and is adopted in its place. (This
  // photo's mean colour also caught the colour button writing back its HSVA round trip, a unit
  // in the last place, which counted as an edit: the best model was then not adopted.)
  const file = path.join(ROOT, '..', 'shared', 'photos', 'dev', 'megaglest_crackedearth_256.png');
  await openApp(page);
  const s = await suggestionsForFile(page, file, 128, 128);
  expect(s.suggestions.slice(0, 2).map((r) => [r.name, r.speckier])).toEqual([['cells', false], ['ridged', true]]);
  expect(s.adopted).toBe(0);
  const cli = JSON.parse(execFileSync(CLI, ['analyze', file, '--crop', '0,0,128,128', '--json'],
    { stdio: ['ignore', 'pipe', 'ignore'] }).toString());
  expect(cli.model.pattern.kind).toBe('cells');
  expectClose(JSON.parse(await page.evaluate(() => window.proctex.getParams())).model, cli.model, 'model');
});

test("the lighting option analyses and ranks the crop again with its lighting divided out, as the CLI's --flatten-lighting", async ({ page }) => {
  // The brick sample's top-left 256² lit from one side (0.6 at the left edge to 1.0 at the
  // right), written as a PNG that the app gets as pixels and the CLI reads.
  const { PNG } = require('pngjs');
  const src = PNG.sync.read(fs.readFileSync(path.join(ROOT, 'www', 'samples', 'skimage_brick_512.png')));
  const lit = new PNG({ width: 256, height: 256 });
  for (let y = 0; y < 256; y++) {
    for (let x = 0; x < 256; x++) {
      const [i, j] = [(y * 256 + x) * 4, (y * src.width + x) * 4];
      for (let c = 0; c < 3; c++) lit.data[i + c] = Math.min(255, Math.round(src.data[j + c] * (0.6 + 0.4 * x / 255)));
      lit.data[i + 3] = 255;
    }
  }
  const file = tmpFile('lit_brick.png');
  fs.writeFileSync(file, PNG.sync.write(lit));
  const cli = (...flags) => JSON.parse(execFileSync(CLI, ['analyze', file, '--crop', '0,0,256,256', '--json', ...flags],
    { stdio: ['ignore', 'pipe', 'ignore'] }).toString());
  await openApp(page);
  const params = async () => JSON.parse(await page.evaluate(() => window.proctex.getParams()));

  const plain = await suggestionsForFile(page, file, 256, 256);
  expect(plain.flatten_lighting).toBe(false);
  const before = await params();
  expect(before.source.flattened_lighting).toBeUndefined();
  // Ticked: the same crop analysed and ranked again, its lighting divided out.
  const flat = await suggestionsAfter(page, 'the lit brick, lighting evened out', () => clickWidget(page, 'lighting'));
  expect(flat.flatten_lighting).toBe(true);
  expect(flat.adopted).toBe(0);
  const after = await params();
  expect(after.source.flattened_lighting).toBe(true);
  expect(after.source.crop).toEqual([0, 0, 256, 256]);
  // What the app adopted is what the CLI chooses with the option, bit for bit up to 1e-4; the
  // plain analysis is the CLI's without it.
  const withOption = cli('--flatten-lighting');
  expect(withOption.source.flattened_lighting).toBe(true);
  expectClose(after.model, withOption.model, 'model');
  expectClose(before.model, cli().model, 'model');
  expect(JSON.stringify(after.model)).not.toBe(JSON.stringify(before.model));
  // Unticked: the photo as it is, the same model as the first time.
  const again = await suggestionsAfter(page, 'the lit brick as it is', () => clickWidget(page, 'lighting'));
  expect(again.flatten_lighting).toBe(false);
  expect((await params()).model).toEqual(before.model);
});

test("a structured model's sliders change the image", async ({ page }) => {
  await openApp(page);
  const s = await suggestionsFor(page, 'skimage_brick_512.png');
  expect(s.suggestions[0].name).not.toBe('noise');
  const square = innerSquare(s.widgets.texture, 192);
  const before = await grab(page, square);
  const [x, y, w, h] = await reveal(page, 'pattern.scale');
  // Drag the scale slider's knob to the rail's left end (finer pattern).
  const params = JSON.parse(await page.evaluate(() => window.proctex.getParams()));
  const scale0 = params.model.pattern.scale;
  await drag(page, [x + 50, y + h / 2], [x + 2, y + h / 2], 8);
  await waitFrames(page, 4);
  const after = JSON.parse(await page.evaluate(() => window.proctex.getParams()));
  expect(after.model.pattern.scale).toBeLessThan(scale0);
  expect((await state(page)).adopted).toBeNull(); // edited: no row is the current model now
  expect(meanDiff(await grab(page, square), before)).toBeGreaterThan(2);
});

test("the adopted structured model's output tone curve toggles and its tones swap", async ({ page }) => {
  await openApp(page);
  const s = await suggestionsFor(page, 'skimage_brick_512.png');
  const params = JSON.parse(await page.evaluate(() => window.proctex.getParams()));
  expect(params.model.kind).toBe('structured');
  expect(params.model.tone.enabled).toBe(true);
  expect(params.model.tone.knots[0].length).toBeGreaterThan(2);
  const square = innerSquare(s.widgets.texture, 192);
  const before = await grab(page, square);
  await clickWidget(page, 'tone');
  await waitFrames(page, 3);
  const after = JSON.parse(await page.evaluate(() => window.proctex.getParams()));
  expect(after.model.tone.enabled).toBe(false);
  const untoned = await grab(page, square);
  expect(meanDiff(untoned, before)).toBeGreaterThan(1);
  // Swap tones: the ramp is read backwards (stops reversed, at -> 1 - at), the image changes.
  await clickWidget(page, 'ramp.swap');
  await waitFrames(page, 3);
  const swapped = JSON.parse(await page.evaluate(() => window.proctex.getParams()));
  const n = after.model.ramp.length;
  expect(swapped.model.ramp.length).toBe(n);
  for (let i = 0; i < n; i++) {
    const a = swapped.model.ramp[i];
    const b = after.model.ramp[n - 1 - i];
    expect(a.at).toBeCloseTo(1 - b.at, 5);
    expect(a.rgb).toEqual(b.rgb);
  }
  expect(meanDiff(await grab(page, square), untoned)).toBeGreaterThan(2);
});

test('the start-up sample suggests models on request; Cancel stops the refinement and ranks what there is', async ({ page }) => {
  await openApp(page);
  // The start-up sample's suggestions start with the button (a new photo's start by themselves).
  expect((await state(page)).suggest_progress).toBeNull();
  await clickWidget(page, 'suggest.start');
  await page.waitForFunction(() => {
    window.proctex.requestRepaint();
    const s = window.proctex.state();
    return s.photo === 'stk_rock_mountain_512.png' && s.suggest_progress && s.widgets['suggest.cancel'];
  }, null, { polling: 50, timeout: 120_000 });
  await clickWidget(page, 'suggest.cancel');
  await page.waitForFunction(() => {
    window.proctex.requestRepaint();
    const s = window.proctex.state();
    return s.suggestions.length > 0 && !s.suggest_progress;
  }, null, { polling: 100, timeout: 60_000 });
  const t = await page.evaluate(() => window.proctex.lastSuggestions());
  expect(t.cancelled).toBe(true);
  expect(t.rows.length).toBe(10);
  // Some families kept their retrieved pattern (no refined distance).
  expect(t.rows.filter((r) => r.retrieval !== null && r.refined === null).length).toBeGreaterThan(0);
});

test('a refinement time budget set in the UI stops the refinement and ranks what there is', async ({ page }) => {
  await openApp(page);
  // The budget control (a drag value showing "none"): click it, type 0.3 s, Enter.
  await page.waitForFunction(() => {
    window.proctex.requestRepaint();
    return !!window.proctex.state().widgets['suggest.budget'];
  }, null, { polling: 100, timeout: 60_000 });
  await clickWidget(page, 'suggest.budget');
  await page.keyboard.press('Control+A');
  await page.keyboard.type('0.3');
  await page.keyboard.press('Enter');
  await waitFrames(page, 3);
  const before = (await page.evaluate(() => window.proctex.lastSuggestions()))?.count ?? 0;
  await page.evaluate(() => window.proctex.loadSample('skimage_brick_512.png'));
  await page.waitForFunction((n) => {
    window.proctex.requestRepaint();
    const t = window.proctex.lastSuggestions();
    const s = window.proctex.state();
    return t && t.count > n && s.photo === 'skimage_brick_512.png' && !s.suggest_progress;
  }, before, { polling: 100, timeout: 120_000 });
  const t = await page.evaluate(() => window.proctex.lastSuggestions());
  expect(t.timedOut).toBe(true);
  expect(t.cancelled).toBe(true);
  expect(t.rows.length).toBe(10);
  // Some families kept their retrieved pattern (no refined distance); the list is ranked.
  expect(t.rows.filter((r) => r.retrieval !== null && r.refined === null).length).toBeGreaterThan(0);
  expect((await state(page)).suggestions.length).toBe(10);
});

test('when the refinement helpers cannot start, the worker refines every family itself', async ({ page }) => {
  // The helper script fails to load (Playwright's routing does not reach a worker's workers,
  // so the page points the helpers at a missing script): each helper is retired and its
  // family goes back to the analysis worker; the ranking is the one the helpers would give.
  await openApp(page);
  await page.evaluate(() => window.proctex.setRefineHelpers(3, './missing-refiner.js'));
  const s = await suggestionsFor(page, 'skimage_gravel_512.png');
  const t = await page.evaluate(() => window.proctex.lastSuggestions());
  expect(t.cancelled).toBe(false);
  expect(t.helped).toBe(0);
  expect(t.rows.length).toBe(10);
  // The families that order the list refined, the others skipped (the classifier orders them), and
  // the same first model as with helpers (the gravel test above).
  expect(t.rows.filter((r) => r.retrieval !== null && r.refined === null && !r.skipped).length).toBe(0);
  expect(s.suggestions[0].name).toBe('noise');
  expect(s.suggest_error).toBeNull();
});
