// The analysis worker. It loads the worker's wasm (analyzeRgba, Suggestions, PyramidSynthesis,
// modelStats, previewRgba) and does everything that takes long: decoding a photo file,
// analysing it (or a crop of it), the automatic model choice (suggest.js: retrieval in the
// pattern database, then refinement one start of a model family per step, shared with helper
// workers on machines with more cores: refiner.js), the Heeger–Bergen raster synthesis of the
// crop (synthesis.js: one round per step), the model statistics for the plots, and the CPU
// preview. This file is the jobs' entry: the current photo and the messages.
//
// Why a worker rather than splitting the work into slices on the UI thread: the expensive steps
// are single calls (the browser's image decode of a 12 MP JPEG, rustfft over the analysis
// image) that cannot be cut into frame-sized pieces without rewriting the analyzer as a state
// machine; in a worker they run whole, in parallel with rendering, and the UI thread only
// receives the params (a few KB) and a preview.
import init, * as wasm from './pkg/proctex_worker.js';
import { decode, pixelsOf, previewOf } from './images.js';
import { enqueue } from './queue.js';
import {
  adoptSuggestion, cancelSuggestions, dropSuggestion, loadPatternDatabase, sendAhead,
  setHelpers, setRefineBudget, startSuggestions,
} from './suggest.js';
import { cancelSynthesis, medianMs, setRoundDelay, synthesise } from './synthesis.js';

const ready = init();
const dbReady = loadPatternDatabase(ready);
// The current photo: { rgba, width, height, name, request }; `request` ({ crop, seed, flatten }):
// how it was last analysed, for suggestions started on request.
let photo = null;
// Whether analyses divide the photo's lighting gradient out (`analyzeRgba`'s option), as the app
// last set it: for every photo and crop from then on.
let flattenLighting = false;

// Analyses a new photo; it becomes the current one only when the analysis succeeds, so a bad
// file leaves the previous photo (and texture) in place.
async function analyseNew(id, name, bitmap, t0, decodeMs, suggest) {
  const rgba = pixelsOf(bitmap);
  const { preview, pw, ph } = previewOf(bitmap);
  const { width, height } = bitmap;
  bitmap.close();
  postMessage({ type: 'progress', id, stage: 'Analysing' });
  const request = { crop: [], seed: 1, flatten: flattenLighting };
  const ahead = suggest ? sendAhead({ rgba, width, height }, request) : null;
  const report = wasm.analyzeRgba(rgba, width, height, new Uint32Array(0), 1, request.flatten);
  photo = { rgba, width, height, name, request };
  postMessage({
    type: 'analysis', id, name, report, ms: performance.now() - t0, decodeMs,
    preview, pw, ph, width, height, suggest,
  }, [preview.buffer]);
  if (suggest) {
    await startSuggestions(photo, id, request, ahead, t0, report);
  } else {
    dropSuggestion(); // the previous photo's refinement is of no use any more
  }
}

async function handle(m) {
  await ready;
  const t0 = performance.now();
  switch (m.type) {
    case 'open': {
      postMessage({ type: 'progress', id: m.id, stage: 'Decoding' });
      // Limits before the browser's decoder takes the memory (see jobs::check_photo_file).
      try { wasm.checkPhotoFile(m.bytes); } catch (e) { throw new Error(`${m.name}: ${e}`); }
      let bitmap;
      try {
        bitmap = await decode(m.bytes);
      } catch (e) {
        throw new Error(`${m.name}: cannot read the image: the file is empty, truncated, ` +
          'corrupt or not an image format the browser decodes');
      }
      try { wasm.checkPhotoSize(bitmap.width, bitmap.height); } catch (e) {
        bitmap.close();
        throw new Error(`${m.name}: ${e}`);
      }
      const decodeMs = performance.now() - t0;
      try {
        await analyseNew(m.id, m.name, bitmap, t0, decodeMs, m.suggest !== false);
      } catch (e) {
        throw new Error(`${m.name}: ${e.message ?? e}`);
      }
      return;
    }
    case 'pixels': {
      const image = new ImageData(new Uint8ClampedArray(m.rgba.buffer), m.width, m.height);
      const bitmap = await createImageBitmap(image);
      try {
        await analyseNew(m.id, m.name, bitmap, t0, 0, m.suggest !== false);
      } catch (e) {
        throw new Error(`${m.name}: ${e.message ?? e}`);
      }
      return;
    }
    case 'analyseOnly': {
      // A sample for the preset gallery: analysed, not made the current photo (as shipped: the
      // lighting option is the user's photos').
      const bitmap = await decode(m.bytes);
      const rgba = pixelsOf(bitmap);
      const report = wasm.analyzeRgba(rgba, bitmap.width, bitmap.height, new Uint32Array(0), 1,
        false);
      bitmap.close();
      postMessage({ type: 'params', id: m.id, params: JSON.stringify(JSON.parse(report).params) });
      return;
    }
    case 'crop': {
      if (!photo) throw new Error('no photo to crop');
      // The crop at the seed the app asks for, with the lighting option as it is now;
      // `suggest: false` (the page without WebGPU, which shows no list): no suggestions.
      const suggest = m.suggest !== false;
      const request = { crop: m.crop, seed: m.seed, flatten: flattenLighting };
      const ahead = suggest ? sendAhead(photo, request) : null;
      const report = wasm.analyzeRgba(photo.rgba, photo.width, photo.height,
        new Uint32Array(m.crop), m.seed, request.flatten);
      photo.request = request;
      postMessage({ type: 'analysis', id: m.id, name: photo.name, report, ms: performance.now() - t0 });
      if (suggest) await startSuggestions(photo, m.id, request, ahead, t0, report);
      else dropSuggestion();
      return;
    }
    case 'suggest': {
      // Suggestions asked for by the user (the start-up sample gets none by itself).
      if (!photo) throw new Error('no photo to suggest models for');
      postMessage({ type: 'suggesting', id: m.id });
      await startSuggestions(photo, m.id, photo.request, null, t0);
      return;
    }
    case 'adopt':
      adoptSuggestion(m.id, m.index, t0);
      return;
    case 'stats': {
      postMessage({ type: 'stats', id: m.id, params: m.params, stats: wasm.modelStats(m.params) });
      return;
    }
    case 'preview': {
      const rgba = wasm.previewRgba(m.params, m.width, m.height);
      postMessage({ type: 'preview', id: m.id, rgba, ms: performance.now() - t0 }, [rgba.buffer]);
      return;
    }
    case 'pyramid':
    case 'solid':
    case 'benchPyramid':
      await synthesise(m, photo, t0);
      return;
    case 'benchRetrieval': {
      // e2e/bench: median milliseconds of each retrieval stage over `reps` runs.
      await dbReady;
      const ms = {};
      for (const stage of ['ffts', 'descriptor', 'retrieval']) {
        ms[stage] = medianMs(m.reps, () => wasm.benchRetrieval(m.rgba, m.width, m.height, stage));
      }
      postMessage({ type: 'bench', id: m.id, ms });
      return;
    }
    default:
      throw new Error(`unknown job ${m.type}`);
  }
}

// Jobs run one at a time, in order (the queue is the suggestions' steps' too).
onmessage = (e) => {
  const m = e.data;
  if (m.type === 'setHelpers') {
    setHelpers(m.n, m.script);
    return;
  }
  if (m.type === 'setRefineBudget') {
    setRefineBudget(m.seconds);
    return;
  }
  if (m.type === 'setFlattenLighting') {
    // Not queued: the app analyses the crop again after it (a 'crop' job), and every analysis
    // queued by then takes it.
    flattenLighting = !!m.on;
    return;
  }
  if (m.type === 'setRoundDelay') {
    setRoundDelay(m.ms);
    return;
  }
  if (m.type === 'cancelPyramid') {
    // Not queued: the running synthesis `m.id` sees it before its next round; a queued one
    // when it starts.
    cancelSynthesis(m.id);
    return;
  }
  if (m.type === 'cancelSuggest') {
    // Not queued: the running refinement sees it before its next step.
    cancelSuggestions();
    return;
  }
  enqueue(() => handle(m), (err) => {
    postMessage({ type: 'error', id: m.id, message: String(err && err.message ? err.message : err) });
  });
};
