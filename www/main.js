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

window.proctex = {
  ready: false,
  samples: SAMPLES,
  loadImage: (bytes, name) => wasm.loadImage(bytes, name || 'image'),
  loadSample: async (name) => wasm.loadImage(await fetchBytes(`samples/${name}`), name),
  getParams: () => wasm.getParams() ?? null,
  setParams: (json) => wasm.setParams(typeof json === 'string' ? json : JSON.stringify(json)),
  setView: (x, y, unitsPerPoint) => wasm.setView(x, y, unitsPerPoint),
  state: () => JSON.parse(wasm.state()),
};

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
  await window.proctex.loadSample(DEFAULT_SAMPLE);
  window.proctex.ready = true;
}

main().catch((e) => show(`Proctex could not start: ${e}`, true));
