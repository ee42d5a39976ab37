// Loader: starts the wasm app on the canvas, loads the built-in sample photo, and exposes the
// automation API on window.proctex (see README.md in this folder).
import init, * as wasm from './pkg/proctex_web.js';

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
  message.textContent = text;
  message.className = isError ? 'error' : '';
  message.style.display = 'block';
}

async function fetchBytes(url) {
  const r = await fetch(url);
  if (!r.ok) throw new Error(`${url}: HTTP ${r.status}`);
  return new Uint8Array(await r.arrayBuffer());
}

// Decodes an image file with the browser (natively, off the main thread, EXIF orientation
// applied) and hands the RGBA pixels to the analysis. A file the browser cannot decode is
// reported in the app, which keeps its current texture.
async function loadImage(bytes, name = 'image') {
  let bitmap;
  try {
    bitmap = await createImageBitmap(new Blob([bytes]), { imageOrientation: 'from-image' });
  } catch (e) {
    wasm.reportError(`${name}: cannot read the image: the file is empty, truncated, corrupt ` +
      'or not an image format the browser decodes');
    return false;
  }
  const { width, height } = bitmap;
  const canvas = new OffscreenCanvas(width, height);
  const ctx = canvas.getContext('2d', { willReadFrequently: true });
  ctx.drawImage(bitmap, 0, 0);
  bitmap.close();
  const rgba = ctx.getImageData(0, 0, width, height).data;
  wasm.loadPixels(new Uint8Array(rgba.buffer), width, height, name);
  return true;
}

window.proctex = {
  ready: false,
  samples: SAMPLES,
  loadImage,
  loadSample: async (name) => loadImage(await fetchBytes(`samples/${name}`), name),
  getParams: () => wasm.getParams() ?? null,
  setParams: (json) => wasm.setParams(typeof json === 'string' ? json : JSON.stringify(json)),
  setView: (x, y, unitsPerPoint) => wasm.setView(x, y, unitsPerPoint),
  state: () => JSON.parse(wasm.state()),
  requestRepaint: () => wasm.requestRepaint(),
};

// Photo in: drag-and-drop anywhere on the page, or paste an image from the clipboard.
function imageFileOf(items) {
  for (const item of items || []) {
    const file = item instanceof File ? item : (item.kind === 'file' ? item.getAsFile() : null);
    if (file) return file;
  }
  return null;
}

async function loadFile(file) {
  const bytes = new Uint8Array(await file.arrayBuffer());
  return loadImage(bytes, file.name || 'pasted image');
}

function installPhotoInputs() {
  // Capture phase: eframe's own canvas handlers would otherwise take the drop (and hand
  // egui the raw bytes, which the app would decode on the UI thread).
  document.addEventListener('dragover', (e) => {
    e.preventDefault(); e.stopPropagation(); e.dataTransfer.dropEffect = 'copy';
  }, true);
  document.addEventListener('drop', (e) => {
    e.preventDefault(); e.stopPropagation();
    const file = imageFileOf(e.dataTransfer && e.dataTransfer.files);
    if (file) loadFile(file);
    else wasm.reportError('Nothing to open: drop an image file.');
  }, true);
  document.addEventListener('paste', (e) => {
    const file = imageFileOf(e.clipboardData && e.clipboardData.items);
    if (file) { e.preventDefault(); loadFile(file); }
  });
}

async function main() {
  await init();
  if (!navigator.gpu) {
    show('This browser has no WebGPU, which Proctex needs to render textures.\n' +
         'Use a current Chrome, Edge or Firefox Nightly, or enable WebGPU.', true);
    return;
  }
  let handle;
  try {
    handle = await wasm.start(document.getElementById('proctex_canvas'));
  } catch (e) {
    show(`Proctex could not start: ${e}`, true);
    return;
  }
  setInterval(() => {
    if (handle.has_panicked()) {
      show(`Proctex stopped on an internal error:\n${handle.panic_message() ?? ''}`, true);
    }
  }, 500);
  installPhotoInputs();
  await window.proctex.loadSample(DEFAULT_SAMPLE);
  window.proctex.ready = true;
}

main().catch((e) => show(`Proctex could not start: ${e}`, true));
