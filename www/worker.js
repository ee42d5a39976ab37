// The analysis worker. It loads the same wasm as the page (only its pure functions: analyzeRgba,
// modelStats, previewRgba) and does everything that takes long: decoding a photo file,
// analysing it (or a crop of it), the model statistics for the plots, and the CPU preview.
//
// Why a worker rather than splitting the work into slices on the UI thread: the expensive steps
// are single calls (the browser's image decode of a 12 MP JPEG, rustfft over the analysis
// image) that cannot be cut into frame-sized pieces without rewriting the analyzer as a state
// machine; in a worker they run whole, in parallel with rendering, and the UI thread only
// receives the params (a few KB) and a preview.
import init, * as wasm from './pkg/proctex_web.js';

const ready = init();
const PREVIEW_SIDE = 1024; // longest side of the preview sent to the UI (crop panel, split view)
let photo = null; // the current photo: { rgba, width, height, name }

async function decode(bytes) {
  const bitmap = await createImageBitmap(new Blob([bytes]), { imageOrientation: 'from-image' });
  return bitmap;
}

function pixelsOf(bitmap) {
  const { width, height } = bitmap;
  const ctx = new OffscreenCanvas(width, height).getContext('2d', { willReadFrequently: true });
  ctx.drawImage(bitmap, 0, 0);
  return new Uint8Array(ctx.getImageData(0, 0, width, height).data.buffer);
}

function previewOf(bitmap) {
  const k = Math.min(1, PREVIEW_SIDE / Math.max(bitmap.width, bitmap.height));
  const w = Math.max(1, Math.round(bitmap.width * k));
  const h = Math.max(1, Math.round(bitmap.height * k));
  const ctx = new OffscreenCanvas(w, h).getContext('2d', { willReadFrequently: true });
  ctx.imageSmoothingQuality = 'high';
  ctx.drawImage(bitmap, 0, 0, w, h);
  return { preview: new Uint8Array(ctx.getImageData(0, 0, w, h).data.buffer), pw: w, ph: h };
}

// Analyses a new photo; it becomes the current one only when the analysis succeeds, so a bad
// file leaves the previous photo (and texture) in place.
async function analyseNew(id, name, bitmap, t0, decodeMs) {
  const rgba = pixelsOf(bitmap);
  const { preview, pw, ph } = previewOf(bitmap);
  const { width, height } = bitmap;
  bitmap.close();
  postMessage({ type: 'progress', id, stage: 'Analysing' });
  const report = wasm.analyzeRgba(rgba, width, height, new Uint32Array(0), 1);
  photo = { rgba, width, height, name };
  postMessage({
    type: 'analysis', id, name, report, ms: performance.now() - t0, decodeMs,
    preview, pw, ph, width, height,
  }, [preview.buffer]);
}

async function handle(m) {
  await ready;
  const t0 = performance.now();
  switch (m.type) {
    case 'open': {
      postMessage({ type: 'progress', id: m.id, stage: 'Decoding' });
      let bitmap;
      try {
        bitmap = await decode(m.bytes);
      } catch (e) {
        throw new Error(`${m.name}: cannot read the image: the file is empty, truncated, ` +
          'corrupt or not an image format the browser decodes');
      }
      const decodeMs = performance.now() - t0;
      try {
        await analyseNew(m.id, m.name, bitmap, t0, decodeMs);
      } catch (e) {
        throw new Error(`${m.name}: ${e.message ?? e}`);
      }
      return;
    }
    case 'pixels': {
      const image = new ImageData(new Uint8ClampedArray(m.rgba.buffer), m.width, m.height);
      const bitmap = await createImageBitmap(image);
      try {
        await analyseNew(m.id, m.name, bitmap, t0, 0);
      } catch (e) {
        throw new Error(`${m.name}: ${e.message ?? e}`);
      }
      return;
    }
    case 'analyseOnly': {
      // A sample for the preset gallery: analysed, not made the current photo.
      const bitmap = await decode(m.bytes);
      const rgba = pixelsOf(bitmap);
      const report = wasm.analyzeRgba(rgba, bitmap.width, bitmap.height, new Uint32Array(0), 1);
      bitmap.close();
      postMessage({ type: 'params', id: m.id, params: JSON.stringify(JSON.parse(report).params) });
      return;
    }
    case 'crop': {
      if (!photo) throw new Error('no photo to crop');
      const report = wasm.analyzeRgba(photo.rgba, photo.width, photo.height,
        new Uint32Array(m.crop), m.seed);
      postMessage({ type: 'analysis', id: m.id, name: photo.name, report, ms: performance.now() - t0 });
      return;
    }
    case 'stats': {
      postMessage({ type: 'stats', id: m.id, params: m.params, stats: wasm.modelStats(m.params) });
      return;
    }
    case 'preview': {
      const rgba = wasm.previewRgba(m.params, m.width, m.height);
      postMessage({ type: 'preview', id: m.id, rgba, ms: performance.now() - t0 }, [rgba.buffer]);
      return;
    }
    default:
      throw new Error(`unknown job ${m.type}`);
  }
}

// Jobs run one at a time, in order.
let queue = Promise.resolve();
onmessage = (e) => {
  const m = e.data;
  queue = queue.then(() => handle(m)).catch((err) => {
    postMessage({ type: 'error', id: m.id, message: String(err && err.message ? err.message : err) });
  });
};
