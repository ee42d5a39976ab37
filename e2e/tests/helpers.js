// Shared helpers: waiting for the app, reading pixels of screenshots, running the CLI.
const { expect } = require('@playwright/test');
const { PNG } = require('pngjs');
const { execFileSync } = require('child_process');
const fs = require('fs');
const os = require('os');
const path = require('path');

const ROOT = path.resolve(__dirname, '..', '..');
const CLI = path.join(ROOT, 'target', 'release', 'proctex');

// The texture view's size in the tests (CSS px): the largest region a check reads is 264²
// (a 256² grab 8 px inside the view), and every render of the view on the software adapter
// costs in proportion to its pixels (a 500×775 view: ~2 s a frame on 2 cores).
const VIEW = [288, 288];

// Opens the app with its texture view at most `view` (CSS px; null: the whole panel).
async function openApp(page, { view = VIEW } = {}) {
  page.on('console', (m) => console.log(`[page] ${m.text()}`));
  page.on('pageerror', (e) => console.log(`[page error] ${e.message}`));
  await page.goto(view ? `/?view=${view[0]}x${view[1]}` : '/');
  await page.waitForFunction(() => window.proctex && window.proctex.ready, null, { timeout: 120_000 });
  await waitFrames(page, 3);
}

async function state(page) {
  return page.evaluate(() => window.proctex.state());
}

// Waits until the app has drawn `n` more frames (so commands and edits have taken effect).
async function waitFrames(page, n) {
  const start = (await state(page)).frame;
  await page.waitForFunction((f) => {
    window.proctex.requestRepaint();
    return window.proctex.state().frame >= f;
  }, start + n, { polling: 50 });
}

// A mouse drag from `from` to `to` ([x, y], CSS px) that the app reads as one: a frame after the
// press and after the motion, so that egui sees the press, the motion and the release in frames
// of their own. On the software adapter one frame (a structured view re-rendered) can outlast
// the whole gesture; egui then reads press and release in one frame as a click at the press.
async function drag(page, [x0, y0], [x1, y1], steps = 6) {
  await page.mouse.move(x0, y0);
  await page.mouse.down();
  await waitFrames(page, 1);
  await page.mouse.move(x1, y1, { steps });
  await waitFrames(page, 1);
  await page.mouse.up();
}

// Screenshot of a rectangle [x, y, w, h] (CSS px, integers) as {width, height, data(RGBA)}.
async function grab(page, [x, y, w, h]) {
  const buf = await page.screenshot({ clip: { x, y, width: w, height: h } });
  return PNG.sync.read(buf);
}

// The luminance of an {width, height, data(RGBA)} image at (x, y).
function luminance(img) {
  const { width: w, data } = img;
  return (x, y) => {
    const i = (y * w + x) * 4;
    return 0.299 * data[i] + 0.587 * data[i + 1] + 0.114 * data[i + 2];
  };
}

// Mean of the squared discrete Laplacian of luminance: high-frequency energy.
function highFrequencyEnergy(img) {
  const { width: w, height: h } = img;
  const lum = luminance(img);
  let s = 0, n = 0;
  for (let y = 1; y < h - 1; y++) {
    for (let x = 1; x < w - 1; x++) {
      const l = 4 * lum(x, y) - lum(x - 1, y) - lum(x + 1, y) - lum(x, y - 1) - lum(x, y + 1);
      s += l * l; n++;
    }
  }
  return s / n;
}

// The luminance gradient's energy along x and y: [Σgx², Σgy²] (central differences).
function gradientEnergy(img) {
  const { width: w, height: h } = img;
  const lum = luminance(img);
  let xx = 0, yy = 0;
  for (let y = 1; y < h - 1; y++) {
    for (let x = 1; x < w - 1; x++) {
      const gx = lum(x + 1, y) - lum(x - 1, y), gy = lum(x, y + 1) - lum(x, y - 1);
      xx += gx * gx; yy += gy * gy;
    }
  }
  return [xx, yy];
}

function channelStats(img) {
  const { data } = img;
  const n = data.length / 4;
  const mean = [0, 0, 0], sq = [0, 0, 0];
  for (let i = 0; i < n; i++) {
    for (let c = 0; c < 3; c++) { const v = data[i * 4 + c]; mean[c] += v; sq[c] += v * v; }
  }
  return mean.map((m, c) => ({ mean: m / n, sd: Math.sqrt(Math.max(0, sq[c] / n - (m / n) ** 2)) }));
}

function tmpFile(name) {
  const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'proctex-e2e-'));
  return path.join(dir, name);
}

// Renders params with the CPU reference renderer; returns the PNG.
function cliRender(paramsJson, { width, height, origin, pixelSize }) {
  const params = tmpFile('params.json');
  fs.writeFileSync(params, paramsJson);
  const out = tmpFile('cpu.png');
  execFileSync(CLI, ['render', params, '-o', out, '--width', String(width), '--height', String(height),
    '--origin', `${origin[0]},${origin[1]}`, '--pixel-size', String(pixelSize)]);
  return PNG.sync.read(fs.readFileSync(out));
}

// An integer-aligned square well inside a widget rectangle.
function innerSquare(rect, size) {
  const [x, y, w, h] = rect;
  const left = Math.ceil(x) + Math.floor((w - size) / 2);
  const top = Math.ceil(y) + Math.floor((h - size) / 2);
  return [left, top, size, size];
}

// The rectangle [x, y, w, h] of the app's widget `name`, scrolled into the viewport first when
// its panel has scrolled it out (the mouse wheel over the panel, as a user scrolls it).
async function reveal(page, name) {
  const { height } = page.viewportSize();
  let r, last = null;
  for (let i = 0; i < 60; i++) {
    const s = await state(page);
    r = s.widgets[name];
    if (!r) throw new Error(`no widget ${name}: ${Object.keys(s.widgets).join(', ')}`);
    const below = r[1] + r[3] > height, above = r[1] < 0;
    // In view, and still: egui scrolls smoothly, over several frames after a wheel event.
    if (!below && !above && JSON.stringify(r) === JSON.stringify(last)) return r;
    if (below || above) {
      await page.mouse.move(r[0] + Math.min(r[2] / 2, 20), below ? height - 40 : 40);
      await page.mouse.wheel(0, below ? 200 : -200);
    }
    last = r;
    await waitFrames(page, 2);
  }
  throw new Error(`widget ${name} stays out of view at ${JSON.stringify(r)}`);
}

// A real mouse click at the centre of the app's widget `name`.
async function clickWidget(page, name) {
  const r = await reveal(page, name);
  await page.mouse.click(r[0] + r[2] / 2, r[1] + r[3] / 2);
  await waitFrames(page, 2);
}

// Waits until the app has finished `n` analyses in total.
async function waitAnalyses(page, n) {
  await page.waitForFunction((k) => {
    window.proctex.requestRepaint();
    const s = window.proctex.state();
    return s.analyses >= k && !s.busy;
  }, n, { polling: 100, timeout: 120_000 });
  await waitFrames(page, 2);
}

// In an open app: saves the rock sample and the grass sample as presets and ticks both as morph
// keys (t = 0). Returns both params documents, parsed.
async function morphRockToGrass(page) {
  const rock = JSON.parse(await page.evaluate(() => window.proctex.getParams()));
  await clickWidget(page, 'preset.save');
  const n = (await state(page)).analyses;
  await clickWidget(page, 'sample.2'); // grass
  await waitAnalyses(page, n + 1);
  const grass = JSON.parse(await page.evaluate(() => window.proctex.getParams()));
  await clickWidget(page, 'preset.save');
  await page.waitForFunction(() => window.proctex.state().presets.length === 2);
  await clickWidget(page, 'preset.0.morph');
  await clickWidget(page, 'preset.1.morph');
  await page.waitForFunction(() => {
    window.proctex.requestRepaint();
    return window.proctex.state().morph_t === 0;
  });
  return { rock, grass };
}

// Loads a shipped sample and waits for its ranked suggestions.
// `crop` ([x, y, w, h], optional): that rectangle of the sample, analysed as a photo of its own.
async function suggestionsFor(page, sample, crop) {
  return suggestionsAfter(page, `${sample}${crop ? ` [${crop}]` : ''}`, async () => {
    if (crop) await page.evaluate(([n, c]) => window.proctex.loadSampleCrop(n, c), [sample, crop]);
    else await page.evaluate((n) => window.proctex.loadSample(n), sample);
  });
}

// `suggestionsFor` a PNG file's top-left `w × h` (a photo that is not a sample), loaded as
// pixels.
async function suggestionsForFile(page, file, w, h) {
  const { PNG } = require('pngjs');
  const png = PNG.sync.read(fs.readFileSync(file));
  const rgba = [];
  for (let y = 0; y < h; y++) {
    for (let x = 0; x < w; x++) {
      const i = (y * png.width + x) * 4;
      rgba.push(png.data[i], png.data[i + 1], png.data[i + 2], 255);
    }
  }
  const name = `${path.basename(file)} [0, 0, ${w}, ${h}]`;
  return suggestionsAfter(page, name, () => page.evaluate(([px, ww, hh, n]) =>
    window.proctex.loadPixels(new Uint8ClampedArray(px), ww, hh, n), [rgba, w, h, name]));
}

// The app's state once the photo that `load` loads is analysed and ranked (`label` names it in
// the log).
async function suggestionsAfter(page, label, load) {
  const before = [
    (await state(page)).analyses,
    await page.evaluate(() => window.proctex.lastSuggestions()?.count ?? 0),
  ];
  await load();
  // The worker's ranking first, without waking the app: each frame of the software adapter
  // costs CPU that the worker and its helpers would otherwise have. The list comes with what
  // decides its order fitted; every other row's fit follows (`fittedMs`): wait for them all.
  await page.waitForFunction((n) => {
    const t = window.proctex.lastSuggestions();
    return (t?.count ?? 0) > n && t.rows.every((r) => r.distance !== null);
  }, before[1], { polling: 200, timeout: 120_000 });
  // This photo's ranking: a ranking received after its analysis (not the previous photo's).
  await page.waitForFunction(([k, n]) => {
    window.proctex.requestRepaint();
    const s = window.proctex.state();
    const t = window.proctex.lastSuggestions();
    return s.analyses > k && s.suggestions.length > 0 && !s.suggest_progress && t && t.count > n;
  }, before, { polling: 200, timeout: 120_000 });
  await waitFrames(page, 3);
  const s = await state(page);
  const t = await page.evaluate(() => window.proctex.lastSuggestions());
  console.log(`${label}: ${s.suggestions.map((r) => `${r.name} ${r.score.toFixed(2)}`).join(', ')} ` +
    `(retrieval to ranking ${t.ms.toFixed(0)} ms, of which the ranking and the best row's final fit ` +
    `${(t.ms - t.refinedMs).toFixed(0)} ms; every row fitted ` +
    `${t.fittedMs === null ? 'with it' : `${t.fittedMs.toFixed(0)} ms`}; ${t.helped} of ${t.refineTasks} ` +
    `refinement starts, ${t.orderHelped} of ${t.orderTasks} fits that order the list and ${t.fitHelped} of ` +
    `${t.fitTasks} final-fit tasks run by ${t.helpers} helper workers)`);
  return s;
}

// Dispatches a drop (or paste) of `file` on the page, as a real drag from the desktop does.
async function dropFile(page, filePath, kind) {
  const bytes = [...fs.readFileSync(filePath)];
  const name = path.basename(filePath);
  await page.evaluate(([b, n, k]) => {
    const dt = new DataTransfer();
    dt.items.add(new File([new Uint8Array(b)], n, { type: 'image/png' }));
    if (k === 'drop') {
      const target = document.getElementById('proctex_canvas');
      target.dispatchEvent(new DragEvent('dragover', { dataTransfer: dt, bubbles: true, cancelable: true }));
      target.dispatchEvent(new DragEvent('drop', { dataTransfer: dt, bubbles: true, cancelable: true }));
    } else {
      document.dispatchEvent(new ClipboardEvent('paste', { clipboardData: dt, bubbles: true, cancelable: true }));
    }
  }, [bytes, name, kind]);
  await page.waitForFunction((n) => {
    window.proctex.requestRepaint();
    return window.proctex.state().photo === n;
  }, name, { polling: 100 });
  await waitFrames(page, 3);
}

module.exports = {
  expect, openApp, state, waitFrames, drag, grab, highFrequencyEnergy, gradientEnergy, channelStats,
  cliRender, CLI,
  innerSquare, reveal, clickWidget, waitAnalyses, morphRockToGrass, suggestionsFor, suggestionsForFile,
  suggestionsAfter, tmpFile, ROOT, dropFile,
};
