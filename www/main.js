// Loader: starts the wasm app on the canvas, runs the analysis worker, wires the photo inputs
// (drop, Open…, paste, camera), and exposes the automation API on window.proctex (see
// README.md in this folder).
import init, * as wasm from './pkg/proctex_web.js';
import { startFallback } from './fallback.js';

const SAMPLES = [
  'stk_rock_mountain_512.png',
  'skimage_gravel_512.png',
  'skimage_grass_512.png',
  'stk_blackrock_256.png',
  'skimage_brick_512.png',
  'stk_wood_planks1_256.png',
];
const DEFAULT_SAMPLE = SAMPLES[0];

const message = document.getElementById('message');
function show(text, isError) {
  message.querySelector('.text').textContent = text;
  message.className = isError ? 'error' : '';
  message.style.display = 'block';
}

async function fetchBytes(url) {
  const r = await fetch(url);
  if (!r.ok) throw new Error(`${url}: HTTP ${r.status}`);
  return new Uint8Array(await r.arrayBuffer());
}

// ---- The worker: one job at a time; replies carry the job id. ----
const worker = new Worker(new URL('./worker.js', import.meta.url), { type: 'module' });
let nextId = 1;
const pending = new Map();
let photoJob = 0; // the photo/crop job whose result the app should show
let suggestJob = 0; // the suggestions asked for the current photo (0: none)
worker.onmessage = (e) => {
  const m = e.data;
  if (m.type === 'progress') {
    if (m.id === photoJob) wasm.analysisProgress(null, m.stage);
    return;
  }
  // Model suggestions of the current photo or crop (unsolicited: they follow its analysis,
  // except the start-up sample's, which start on request: `suggestJob`).
  if (m.type === 'suggestProgress' || m.type === 'suggestions' || m.type === 'suggestError') {
    if ((m.id !== photoJob && m.id !== suggestJob) || !appRunning) return;
    if (m.type === 'suggestProgress') wasm.suggestionProgress(m.done, m.total);
    else if (m.type === 'suggestError') wasm.suggestionsFailed(m.message);
    else {
      lastSuggestions = {
        rows: JSON.parse(m.rows), ms: m.ms, requestMs: m.requestMs, refinedMs: m.refinedMs, cancelled: m.cancelled, timedOut: m.timedOut,
        helpers: m.helpers, helped: m.helped, refineTasks: m.refineTasks, fitTasks: m.fitTasks,
        fitHelped: m.fitHelped,
        orderTasks: m.orderTasks, orderHelped: m.orderHelped, nearer: m.nearer,
        count: (lastSuggestions?.count ?? 0) + 1,
        id: m.id, fittedMs: null,
      };
      wasm.suggestionsDone(m.rows, m.thumbs, m.cancelled, m.timedOut, m.best ?? undefined);
    }
    return;
  }
  // A row of the list fitted after it came (the list fits only what decides its order).
  if (m.type === 'suggestionFitted') {
    if ((m.id !== photoJob && m.id !== suggestJob) || !appRunning) return;
    if (lastSuggestions?.id === m.id) {
      lastSuggestions.rows[m.index] = JSON.parse(m.row);
      if (m.last) lastSuggestions.fittedMs = m.ms;
    }
    wasm.suggestionFitted(m.index, m.row, m.thumb);
    return;
  }
  // The Heeger–Bergen syntheses' rounds (their results resolve the jobs below).
  if (m.type === 'pyramidProgress') {
    if (!appRunning) return;
    if (m.id === pyramidJob) wasm.pyramidProgress(m.done, m.total);
    else if (m.id === solidJob) wasm.solidProgress(m.done, m.total);
    return;
  }
  const resolve = pending.get(m.id);
  pending.delete(m.id);
  if (resolve) resolve(m);
};
worker.onerror = (e) => reportError(`The analysis worker failed: ${e.message}`);
function job(msg, transfer = []) {
  const id = nextId++;
  return [id, new Promise((resolve) => {
    pending.set(id, resolve);
    worker.postMessage({ ...msg, id }, transfer);
  })];
}

let appRunning = false;
let pyramidJob = 0; // the Heeger–Bergen synthesis the app waits for (0: none)
let solidJob = 0; // the Heeger–Bergen solid texture the app waits for (0: none)

// The Heeger–Bergen synthesis of crop [x, y, w, h] of the current photo, for the app's
// pyramid view; a new one supersedes the one running (which is cancelled).
// `mix`: absent, or JSON { sample: name | params: json, m } for a texture mixture (B); `a`:
// absent (the crop), or the same JSON for the texture synthesised (A).
async function synthesisePyramid(x, y, w, h, seed, mix, a) {
  if (pyramidJob) worker.postMessage({ type: 'cancelPyramid', id: pyramidJob });
  const [id, reply] = job({
    type: 'pyramid', crop: [x, y, w, h], seed, mix: mix ? JSON.parse(mix) : undefined,
    a: a ? JSON.parse(a) : undefined,
  });
  pyramidJob = id;
  const m = await reply;
  if (m.id !== pyramidJob) return;
  pyramidJob = 0;
  if (m.type === 'error') wasm.pyramidFailed(m.message);
  else if (m.cancelled) wasm.pyramidCancelled();
  else wasm.pyramidDone(m.rgba, m.width, m.height, m.ms);
}

// The Heeger–Bergen solid texture (n³ voxels) of crop [x, y, w, h] of the current photo, for
// the sphere and cube views; a new one supersedes the one running (which is cancelled).
async function synthesiseSolid(x, y, w, h, seed, n) {
  if (solidJob) worker.postMessage({ type: 'cancelPyramid', id: solidJob });
  const [id, reply] = job({ type: 'solid', crop: [x, y, w, h], seed, n });
  solidJob = id;
  const m = await reply;
  if (m.id !== solidJob) return;
  solidJob = 0;
  if (m.type === 'error') wasm.solidFailed(m.message);
  else if (m.cancelled) wasm.solidCancelled();
  else wasm.solidDone(m.rgba, m.n, m.voxelsPerUnit, m.ms);
}

// An RGBA8 image as a PNG download (the canvas encodes it losslessly: every alpha is 255).
async function downloadPng(name, rgba, width, height) {
  const canvas = new OffscreenCanvas(width, height);
  canvas.getContext('2d').putImageData(
    new ImageData(new Uint8ClampedArray(rgba.buffer, rgba.byteOffset, rgba.length), width, height), 0, 0);
  const blob = await canvas.convertToBlob({ type: 'image/png' });
  window.proctex.lastPng = { name, bytes: blob.size, width, height };
  const url = URL.createObjectURL(blob);
  const a = document.createElement('a');
  a.href = url; a.download = name;
  document.body.appendChild(a); a.click(); a.remove();
  setTimeout(() => URL.revokeObjectURL(url), 60_000);
}
function reportError(text) {
  if (appRunning) wasm.reportError(text);
  else if (fallback) fallback.showError(text);
  else show(text, true);
}

// A new photo (file bytes or camera pixels) → worker → app. Resolves true when analysed.
async function analysePhoto(msg, transfer, name) {
  const [id, reply] = job(msg, transfer);
  photoJob = id;
  suggestJob = 0;
  if (appRunning) wasm.analysisProgress(name, 'Decoding');
  const m = await reply;
  if (m.id !== photoJob) return false; // superseded by a later photo
  if (m.type === 'error') {
    reportError(m.message);
    return false;
  }
  lastReport = m.report;
  if (appRunning) {
    wasm.analysisDone(m.report, m.name, m.ms, m.preview, m.pw, m.ph, m.width, m.height);
    if (m.suggest === false) wasm.suggestionsOnRequest();
  } else if (fallback) {
    await showCpuResult(m.name, m.ms);
  }
  lastTimings = { ms: m.ms, decodeMs: m.decodeMs };
  return true;
}
let lastReport = null;
let lastSuggestions = null;
// The last pick adopted from the list: its row, the milliseconds of its final fit in the
// worker, that fit's tasks and how many the helper workers ran (0 when it ran in one piece).
let lastAdoption = null;
let lastTimings = null;

// `suggest: false`: the model suggestions wait until the user asks (the start-up sample: its
// 20–40 s of refinement would compete with the first frames and delay the analysis of the
// user's own first photo, and most users replace the sample at once). The page without WebGPU
// shows no list, so it never asks for one.
async function loadImage(bytes, name = 'image', { suggest = fallback === null } = {}) {
  const copy = new Uint8Array(bytes); // transferable, whatever the caller passed
  return analysePhoto({ type: 'open', bytes: copy, name, suggest }, [copy.buffer], name);
}

// The built-in sample shown at start-up (and in the no-WebGPU fallback): its suggestions wait
// for the "Suggest models" click.
async function loadStartupSample() {
  return loadImage(await fetchBytes(`samples/${DEFAULT_SAMPLE}`), DEFAULT_SAMPLE, { suggest: false });
}

async function loadPixels(rgba, width, height, name) {
  const copy = new Uint8Array(rgba);
  return analysePhoto({ type: 'pixels', rgba: copy, width, height, name, suggest: fallback === null },
    [copy.buffer], name);
}

// Crop re-analysis: requests while one runs are coalesced into the latest.
let cropBusy = false;
let cropNext = null;
async function pumpCrop() {
  if (cropBusy || !cropNext) return;
  cropBusy = true;
  const c = cropNext;
  cropNext = null;
  const [id, reply] = job({ type: 'crop', crop: c.crop, seed: c.seed });
  photoJob = id;
  suggestJob = 0;
  wasm.analysisProgress(null, 'Analysing the crop');
  const m = await reply;
  if (m.id === photoJob) {
    if (m.type === 'error') wasm.reportError(m.message);
    else wasm.analysisDone(m.report, m.name, m.ms, undefined, 0, 0, 0, 0);
  }
  cropBusy = false;
  pumpCrop();
}

// Model statistics for the plots, coalesced the same way.
let statsBusy = false;
let statsNext = null;
async function pumpStats() {
  if (statsBusy || !statsNext) return;
  statsBusy = true;
  const params = statsNext;
  statsNext = null;
  const [, reply] = job({ type: 'stats', params });
  const m = await reply;
  if (m.type === 'stats') wasm.modelStatsDone(m.params, m.stats);
  statsBusy = false;
  pumpStats();
}

// ---- Photo inputs ----
function imageFileOf(items) {
  for (const item of items || []) {
    const file = item instanceof File ? item : (item.kind === 'file' ? item.getAsFile() : null);
    if (file) return file;
  }
  return null;
}

const isJson = (file) => file.type === 'application/json' || /\.json$/i.test(file.name || '');

// JSON text from a file, a drop or a paste: a params document replaces the params, a presets
// library adds its presets; anything else is reported.
function importJson(text, what) {
  if (!appRunning) {
    reportError(`${what}: params and presets files open in the full app, which needs WebGPU`);
    return false;
  }
  let doc;
  try { doc = JSON.parse(text); } catch (e) {
    wasm.reportError(`${what}: not JSON (${e.message})`);
    return false;
  }
  if (doc && doc.format === 'proctex/1') {
    try { wasm.setParams(text); } catch (e) {
      wasm.reportError(`${what}: ${e}`);
      return false;
    }
    return true;
  }
  wasm.importPresets(text); // a library, or an error message naming what is wrong
  return true;
}

// Share links: the params JSON, base64url, in the fragment (#p=…); encoded and decoded in
// wasm (proctex::share), which also refuses anything but a texture in a link.
function shareLink(json) {
  return `${location.origin}${location.pathname}${wasm.shareFragment(json)}`;
}

// The most bytes the page reads from one file: the analyzer's limit (limits::MAX_FILE_BYTES),
// checked before reading so that a huge file costs no memory.
const MAX_FILE_BYTES = 256 * 1024 * 1024;
function tooBig(file) {
  if (file.size <= MAX_FILE_BYTES) return false;
  reportError(`${file.name || 'the file'}: more than 256 MiB; no photo or params file ` +
    'needs that many (a photo converts to PNG or JPEG)');
  return true;
}

// An image is analysed; a .json file (params or a presets library) is imported.
async function loadFile(file) {
  if (tooBig(file)) return false;
  if (isJson(file)) return importJson(await file.text(), file.name);
  const bytes = new Uint8Array(await file.arrayBuffer());
  return loadImage(bytes, file.name || 'pasted image');
}

const presetInput = document.createElement('input');
presetInput.type = 'file';
presetInput.accept = '.json,application/json';
presetInput.style.display = 'none';
document.body.appendChild(presetInput);
presetInput.addEventListener('change', async () => {
  const f = presetInput.files && presetInput.files[0];
  if (f && !tooBig(f)) wasm.importPresets(await f.text());
  presetInput.value = '';
});

function downloadText(name, text) {
  const type = name.endsWith('.json') ? 'application/json' : 'text/plain';
  const url = URL.createObjectURL(new Blob([text], { type }));
  const a = document.createElement('a');
  a.href = url; a.download = name;
  document.body.appendChild(a); a.click(); a.remove();
  setTimeout(() => URL.revokeObjectURL(url), 10_000);
}

const fileInput = document.createElement('input');
fileInput.type = 'file';
fileInput.accept = 'image/*';
fileInput.style.display = 'none';
document.body.appendChild(fileInput);
fileInput.addEventListener('change', () => {
  const f = fileInput.files && fileInput.files[0];
  if (f) loadFile(f);
  fileInput.value = '';
});

function installPhotoInputs() {
  // Another tab saved presets: the app shows its library (see web/src/preset_store.rs).
  window.addEventListener('storage', (e) => {
    if (e.key === 'proctex.presets' || e.key === null) wasm.presetsChangedElsewhere();
  });
  // Capture phase: eframe's own canvas handlers would otherwise take the drop (and hand
  // egui the raw bytes, which the app would decode on the UI thread).
  document.addEventListener('dragover', (e) => {
    e.preventDefault(); e.stopPropagation(); e.dataTransfer.dropEffect = 'copy';
  }, true);
  document.addEventListener('drop', (e) => {
    e.preventDefault(); e.stopPropagation();
    const file = imageFileOf(e.dataTransfer && e.dataTransfer.files);
    if (file) loadFile(file);
    else reportError('Nothing to open: drop an image file.');
  }, true);
  document.addEventListener('paste', (e) => {
    const file = imageFileOf(e.clipboardData && e.clipboardData.items);
    if (file) { e.preventDefault(); loadFile(file); return; }
    const text = e.clipboardData && e.clipboardData.getData('text/plain');
    if (text && text.trim().startsWith('{')) { e.preventDefault(); importJson(text, 'pasted text'); }
  });
}

// Camera: live preview in an overlay, Capture analyses the current frame.
const camera = document.getElementById('camera');
const video = document.getElementById('camera_video');
let stream = null;
function closeCamera() {
  if (stream) stream.getTracks().forEach((t) => t.stop());
  stream = null;
  video.srcObject = null;
  camera.hidden = true;
}
async function openCamera() {
  if (!navigator.mediaDevices || !navigator.mediaDevices.getUserMedia) {
    reportError('Camera: this browser gives the page no camera access ' +
      '(it needs a secure context: https or localhost).');
    return;
  }
  try {
    stream = await navigator.mediaDevices.getUserMedia({
      video: { width: { ideal: 1920 }, height: { ideal: 1080 } }, audio: false,
    });
  } catch (e) {
    const why = {
      NotAllowedError: 'permission was denied',
      NotFoundError: 'no camera was found',
      NotReadableError: 'the camera is in use by another program',
    }[e.name] || e.message || String(e);
    reportError(`Camera: ${why}.`);
    return;
  }
  video.srcObject = stream;
  camera.hidden = false;
  await video.play().catch(() => {});
}
async function capture() {
  if (!stream || video.videoWidth === 0) {
    reportError('Camera: no frame yet; wait for the preview and try again.');
    return false;
  }
  const w = video.videoWidth, h = video.videoHeight;
  const ctx = new OffscreenCanvas(w, h).getContext('2d', { willReadFrequently: true });
  ctx.drawImage(video, 0, 0, w, h);
  const rgba = ctx.getImageData(0, 0, w, h).data;
  closeCamera();
  return loadPixels(rgba, w, h, `camera ${w}×${h}`);
}
document.getElementById('camera_capture').addEventListener('click', () => capture());
document.getElementById('camera_cancel').addEventListener('click', closeCamera);

// PNG tile export: the app renders the seamless tile in strips and hands over PNG scanlines
// (filter byte + RGB samples); the browser's own zlib (CompressionStream 'deflate') compresses
// them as they come, and the chunks are wrapped into a PNG file at the end. Why here and not
// in wasm: native-speed deflate, no encoder in the wasm, and only compressed bytes are kept.
const CRC_TABLE = (() => {
  const t = new Uint32Array(256);
  for (let n = 0; n < 256; n++) {
    let c = n;
    for (let k = 0; k < 8; k++) c = c & 1 ? 0xedb88320 ^ (c >>> 1) : c >>> 1;
    t[n] = c >>> 0;
  }
  return t;
})();

function pngChunk(type, data) {
  const out = new Uint8Array(12 + data.length);
  const view = new DataView(out.buffer);
  view.setUint32(0, data.length);
  for (let i = 0; i < 4; i++) out[4 + i] = type.charCodeAt(i);
  out.set(data, 8);
  let c = 0xffffffff;
  for (let i = 4; i < 8 + data.length; i++) c = CRC_TABLE[(c ^ out[i]) & 0xff] ^ (c >>> 8);
  view.setUint32(8 + data.length, (c ^ 0xffffffff) >>> 0);
  return out;
}

let tileWriter = null;

function tileBegin(width, height, bits) {
  if (tileWriter) tileWriter.writer.abort().catch(() => {});
  const cs = new CompressionStream('deflate');
  const writer = cs.writable.getWriter();
  const chunks = [];
  const reader = cs.readable.getReader();
  const reading = (async () => {
    for (;;) {
      const { value, done } = await reader.read();
      if (done) return;
      chunks.push(value);
    }
  })();
  tileWriter = { width, height, bits, writer, chunks, reading };
}

function tileRows(bytes) {
  if (tileWriter) tileWriter.writer.write(bytes).catch(() => {});
}

async function tileEnd(name) {
  const t = tileWriter;
  tileWriter = null;
  if (!t) return;
  await t.writer.close();
  await t.reading;
  const ihdr = new Uint8Array(13);
  const v = new DataView(ihdr.buffer);
  v.setUint32(0, t.width);
  v.setUint32(4, t.height);
  ihdr[8] = t.bits; ihdr[9] = 2; // RGB
  // One IDAT per compressed chunk, each at most 1 MiB.
  const idats = [];
  for (const c of t.chunks) {
    for (let o = 0; o < c.length; o += 1 << 20) idats.push(pngChunk('IDAT', c.subarray(o, o + (1 << 20))));
  }
  const signature = new Uint8Array([137, 80, 78, 71, 13, 10, 26, 10]);
  const blob = new Blob([signature, pngChunk('IHDR', ihdr), ...idats, pngChunk('IEND', new Uint8Array(0))],
    { type: 'image/png' });
  window.proctex.lastTile = { name, bytes: blob.size, width: t.width, height: t.height, bits: t.bits };
  const url = URL.createObjectURL(blob);
  const a = document.createElement('a');
  a.href = url; a.download = name;
  document.body.appendChild(a); a.click(); a.remove();
  setTimeout(() => URL.revokeObjectURL(url), 60_000);
}

function tileAbort() {
  if (tileWriter) tileWriter.writer.abort().catch(() => {});
  tileWriter = null;
}

// What the app calls (window.proctexHost): see web/src/app/bridge.rs `host`.
window.proctexHost = {
  openFile: () => fileInput.click(),
  openCamera: () => { openCamera(); },
  loadSample: (name) => { window.proctex.loadSample(name); },
  analyseCrop: (x, y, w, h, seed) => { cropNext = { crop: [x, y, w, h], seed }; pumpCrop(); },
  modelStats: (params) => { statsNext = params; pumpStats(); },
  adoptSuggestion: async (index) => {
    const [, reply] = job({ type: 'adopt', index });
    const m = await reply;
    if (m.type === 'error') wasm.suggestionsFailed(m.message);
    else if (!m.superseded) {
      lastAdoption = {
        index: m.index, ms: m.ms, fitTasks: m.fitTasks ?? 0, fitHelped: m.fitHelped ?? 0,
        helpers: m.helpers ?? 0, count: (lastAdoption?.count ?? 0) + 1,
      };
      wasm.suggestionAdopted(m.index, m.report);
    }
  },
  // The current photo's suggestions, asked for with the app's "Suggest models" button.
  suggestModels: async () => {
    const [id, reply] = job({ type: 'suggest' });
    suggestJob = id;
    const m = await reply;
    if (m.type === 'error' && suggestJob === id) wasm.suggestionsFailed(m.message);
  },
  cancelSuggestions: () => worker.postMessage({ type: 'cancelSuggest' }),
  synthesisePyramid: (x, y, w, h, seed, mix, a) => {
    synthesisePyramid(x, y, w, h, seed, mix, a);
  },
  cancelPyramid: () => worker.postMessage({ type: 'cancelPyramid', id: pyramidJob }),
  synthesiseSolid: (x, y, w, h, seed, n) => { synthesiseSolid(x, y, w, h, seed, n); },
  cancelSolid: () => worker.postMessage({ type: 'cancelPyramid', id: solidJob }),
  downloadPng: (name, rgba, width, height) => {
    downloadPng(name, rgba, width, height).catch((e) => wasm.reportError(`PNG: ${e}`));
  },
  // The refinement's time budget in seconds (0: none), for the running refinement and the next.
  setRefineBudget: (seconds) => worker.postMessage({ type: 'setRefineBudget', seconds }),
  setFlattenLighting: (on) => worker.postMessage({ type: 'setFlattenLighting', on }),
  downloadText,
  tileBegin,
  tileRows,
  tileEnd: (name) => { tileEnd(name).catch((e) => wasm.reportError(`PNG tile: ${e}`)); },
  tileAbort,
  copyText: (text) => {
    window.proctex.lastCopied = text;
    if (navigator.clipboard) navigator.clipboard.writeText(text).catch(() => {});
  },
  openPresets: () => presetInput.click(),
  copyShareLink: (json) => {
    const link = shareLink(json);
    window.proctex.lastShareLink = link;
    if (navigator.clipboard) navigator.clipboard.writeText(link).catch(() => {});
  },
};

window.proctex = {
  ready: false,
  samples: SAMPLES,
  loadImage,
  loadPixels,
  loadSample: async (name) => loadImage(await fetchBytes(`samples/${name}`), name),
  // e2e/bench: rectangle [x, y, w, h] of a sample, analysed as a photo of its own.
  loadSampleCrop: async (name, [x, y, w, h]) => {
    const bitmap = await createImageBitmap(new Blob([await fetchBytes(`samples/${name}`)]),
      { colorSpaceConversion: 'none', premultiplyAlpha: 'none' });
    const ctx = new OffscreenCanvas(w, h).getContext('2d', { willReadFrequently: true });
    ctx.drawImage(bitmap, x, y, w, h, 0, 0, w, h);
    bitmap.close();
    return loadPixels(ctx.getImageData(0, 0, w, h).data, w, h, `${name} [${x}, ${y}, ${w}, ${h}]`);
  },
  capture,
  getParams: () => wasm.getParams() ?? null,
  setParams: (json) => wasm.setParams(typeof json === 'string' ? json : JSON.stringify(json)),
  setView: (x, y, unitsPerPoint) => wasm.setView(x, y, unitsPerPoint),
  setViewMode: (mode) => wasm.setViewMode(mode),
  // The pyramid view's texture mixture: `source` (B) 'sample:NAME', 'gallery:NAME',
  // 'preset:NAME' or 'crop' (null: none), `m` from 0 (A's synthesis) to 1 (B's), `a` (A) likewise (null: the photo's crop).
  setPyramidMix: (source, m, a) => wasm.setPyramidMix(source ?? undefined, m ?? 0, a ?? undefined),
  // The sphere and cube views' texture: 'procedural' or 'heeger-bergen' (the crop's raster
  // volume, `side`³ voxels: 64 or 128).
  setSolidSource: (source, side) => wasm.setSolidSource(source, side ?? 64),
  setFlatShader: (on) => wasm.setFlatShader(on),
  setFrameCache: (on) => wasm.setFrameCache(on),
  setViewLimit: (width, height) => wasm.setViewLimit(width, height),
  setTileOptions: (size, bits, forceCpu) => wasm.setTileOptions(size, bits, !!forceCpu),
  state: () => JSON.parse(wasm.state()),
  requestRepaint: () => wasm.requestRepaint(),
  importPresets: (text) => wasm.importPresets(text),
  shareLink: () => { const p = wasm.getParams(); return p ? shareLink(p) : null; },
  getPresets: () => wasm.getPresets() ?? null,
  // e2e/bench: median milliseconds of the retrieval stages (worker, `reps` runs each) for an
  // RGBA image.
  benchPyramid: async (rgba, width, height, reps) => {
    const [, reply] = job({ type: 'benchPyramid', rgba, width, height, reps });
    const m = await reply;
    if (m.type !== 'bench') throw new Error(m.message ?? m.type);
    return m.ms;
  },
  benchRetrieval: async (rgba, width, height, reps) => {
    const [, reply] = job({ type: 'benchRetrieval', rgba, width, height, reps });
    const m = await reply;
    if (m.type !== 'bench') throw new Error(m.message ?? m.type);
    return m.ms;
  },
  lastTimings: () => lastTimings,
  // The last ranked suggestions: rows (name, score, distance, retrieval, refined), the
  // milliseconds from retrieval to ranking, whether Cancel (or the time budget: `timedOut`)
  // cut the refinement, how many of its starts the helper workers refined (`helped` of
  // `refineTasks`, by `helpers` helpers), and how many rankings the page has received (`count`).
  lastSuggestions: () => lastSuggestions,
  lastAdoption: () => lastAdoption,
  // e2e/bench: at most `n` helper workers refine families for the next suggestions (default:
  // the cores beyond the worker's and the page's, at most 3), to time refinement with and
  // without them in one run; `script` (tests) starts them from another script URL.
  setRefineHelpers: (n, script) => worker.postMessage({ type: 'setHelpers', n, script }),
  // e2e: each round of the pyramid and solid syntheses waits `ms` first (0: none), so that a
  // test can press Cancel between rounds however fast the machine runs them.
  setSynthesisRoundDelay: (ms) => worker.postMessage({ type: 'setRoundDelay', ms }),
};

// Without WebGPU: say so in plain words, and keep the inputs working: every photo opened,
// dropped or pasted is analysed in the worker and shown as its CPU reference render, with the
// plots and the exports that need no GPU (www/fallback.js).
let fallback = null;
async function cpuFallback(notice) {
  document.getElementById('proctex_canvas').style.display = 'none';
  fallback = startFallback(notice, {
    openFile: () => fileInput.click(),
    download: downloadText,
    exportShader: (params, format) => wasm.exportShader(params, format),
    // The worker takes the option for every analysis from now on; the current photo is
    // analysed again with it (a crop job over the whole photo, at the analysis seed 1).
    setLighting: (on) => {
      worker.postMessage({ type: 'setFlattenLighting', on });
      analysePhoto({ type: 'crop', crop: [], seed: 1, suggest: false }, [], 'the photo');
    },
  });
  installPhotoInputs();
  await loadStartupSample();
  window.proctex.ready = true;
}

// The CPU preview of the last analysis, in the fallback panel.
async function showCpuResult(name, ms) {
  const size = 384;
  const params = JSON.stringify(JSON.parse(lastReport).params);
  const [, reply] = job({ type: 'preview', params, width: size, height: size });
  const m = await reply;
  if (m.type !== 'preview') { fallback.showError(m.message); return; }
  fallback.showResult(name, ms, lastReport, m.rgba, size);
  window.proctex.cpuPreview = { width: size, height: size, ms: m.ms, photo: name };
}

async function main() {
  // Offline after one visit (sw.js). Service workers exist only on https and localhost.
  if ('serviceWorker' in navigator) navigator.serviceWorker.register('sw.js').catch(() => {});
  await init();
  const howTo = 'Proctex draws its textures live with WebGPU: use a current Chrome or Edge, ' +
    'Safari 26 or later, or Firefox with WebGPU turned on. Until then this page still analyses ' +
    'your photos (open, drop or paste one) and shows each result drawn on the CPU, with its ' +
    'plots and exports.';
  if (!navigator.gpu) {
    await cpuFallback(`This browser has no WebGPU. ${howTo}`);
    return;
  }
  let handle;
  try {
    handle = await wasm.start(document.getElementById('proctex_canvas'));
  } catch (e) {
    console.warn('WebGPU could not start:', e); // the adapter's own words, for bug reports
    await cpuFallback('This browser has WebGPU, but could not start it on this device (its ' +
      `graphics driver or settings block it). ${howTo}`);
    return;
  }
  appRunning = true;
  // ?view=WxH: the texture view at most W×H CSS px, at the top-left of its panel (tests and
  // screenshots: every render of the view costs in proportion to its pixels).
  const viewLimit = /^(\d+)x(\d+)$/.exec(new URLSearchParams(location.search).get('view') ?? '');
  if (viewLimit) wasm.setViewLimit(Number(viewLimit[1]), Number(viewLimit[2]));
  setInterval(() => {
    if (handle.has_panicked()) {
      show(`Proctex stopped on an internal error:\n${handle.panic_message() ?? ''}\n` +
        'Reload the page to continue.', true);
    }
  }, 500);
  installPhotoInputs();
  await loadStartupSample();
  // A share link: the texture in the fragment replaces the sample's params.
  if (location.hash.startsWith('#p=')) {
    try { wasm.openShareFragment(location.hash); } catch (e) { wasm.reportError(`${e}`); }
  }
  window.proctex.ready = true;
  buildGallery();
}

// The built-in preset gallery: every shipped sample, analysed in the worker after start-up.
async function buildGallery() {
  for (const name of SAMPLES) {
    try {
      const bytes = await fetchBytes(`samples/${name}`);
      const [, reply] = job({ type: 'analyseOnly', bytes, name }, [bytes.buffer]);
      const m = await reply;
      if (m.type === 'params') wasm.addGalleryPreset(name.replace(/\.png$/, ''), m.params);
    } catch (e) {
      console.warn(`gallery: ${name}: ${e}`);
    }
  }
  window.proctex.galleryReady = true;
}

main().catch((e) => show(`Proctex could not start: ${e}`, true));
