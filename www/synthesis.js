// The analysis worker's raster syntheses (Heeger–Bergen, plane or solid): their rounds, one per
// macrotask so that Cancel gets in between, and the textures a mixture takes.
import * as wasm from './pkg/proctex_worker.js';
import { decode, pixelsOf } from './images.js';

// Job `m` ('pyramid', 'solid' or 'benchPyramid') on the current `photo` (or on a mixture's
// textures), from the worker's queue; `t0`: when it started.
export async function synthesise(m, photo, t0) {
  switch (m.type) {
    case 'pyramid': {
      // The Heeger–Bergen synthesis of the current photo's crop, or of A (a shipped sample or a
      // preset's texture, whole).
      let a;
      if (m.a) a = { ...(await mixtureSource(m.a, photo)), crop: new Uint32Array(0) };
      else if (photo) a = { ...photo, crop: new Uint32Array(m.crop) };
      else throw new Error('no photo to synthesise from');
      let job;
      if (m.mix) {
        // A texture mixture with B: a shipped sample photo or a preset's texture.
        const b = await mixtureSource(m.mix, photo);
        job = wasm.PyramidSynthesis.mixture(a.rgba, a.width, a.height, a.crop, m.seed,
          b.rgba, b.width, b.height, m.mix.m);
      } else {
        job = new wasm.PyramidSynthesis(a.rgba, a.width, a.height, a.crop, m.seed);
      }
      await runRounds(m.id, job, t0, () => {
        const [width, height] = job.size();
        const rgba = job.rgba();
        return [{ rgba, width, height }, [rgba.buffer]];
      });
      return;
    }
    case 'solid': {
      // The Heeger–Bergen solid texture (an n³ volume) of the current photo's crop.
      if (!photo) throw new Error('no photo to synthesise from');
      const job = new wasm.SolidSynthesis(photo.rgba, photo.width, photo.height,
        new Uint32Array(m.crop), m.seed, m.n);
      await runRounds(m.id, job, t0, () => {
        const rgba = job.rgba();
        return [{ rgba, n: job.side(), voxelsPerUnit: job.voxelsPerUnit() }, [rgba.buffer]];
      });
      return;
    }
    case 'benchPyramid': {
      // e2e/bench: median milliseconds of the synthesis and of the FFTs it needs, and of a
      // 64³ solid texture (once: seconds).
      const ms = {};
      for (const stage of ['ffts', 'synthesis', 'solid']) {
        ms[stage] = medianMs(stage === 'solid' ? 1 : m.reps,
          () => wasm.benchPyramid(m.rgba, m.width, m.height, stage));
      }
      postMessage({ type: 'bench', id: m.id, ms });
      return;
    }
    default:
      throw new Error(`unknown synthesis ${m.type}`);
  }
}

// Benchmarks: the median milliseconds of `reps` calls of `f`.
export function medianMs(reps, f) {
  const t = [];
  for (let i = 0; i < reps; i++) {
    const s = performance.now();
    f();
    t.push(performance.now() - s);
  }
  t.sort((a, b) => a - b);
  return t[t.length >> 1];
}

// A texture of a mixture: a shipped sample photo ({ sample: name }), a preset's texture
// ({ params: json }, rendered on the CPU at 256²) or the current photo's crop ({ crop: [x, y,
// w, h] }), as RGBA.
const MIX_PRESET_SIDE = 256;
async function mixtureSource(mix, photo) {
  if (mix.crop) {
    if (!photo) throw new Error('no photo to mix');
    const [x, y, w, h] = mix.crop;
    if (!(w > 0 && h > 0 && x + w <= photo.width && y + h <= photo.height)) {
      throw new Error(`the crop ${w}×${h} at ${x}, ${y} reaches outside the ${photo.width}×${photo.height} photo`);
    }
    const rgba = new Uint8Array(w * h * 4);
    for (let row = 0; row < h; row++) {
      const start = ((y + row) * photo.width + x) * 4;
      rgba.set(photo.rgba.subarray(start, start + w * 4), row * w * 4);
    }
    return { rgba, width: w, height: h };
  }
  if (mix.sample) {
    const r = await fetch(new URL(`./samples/${mix.sample}`, import.meta.url));
    if (!r.ok) throw new Error(`${mix.sample}: HTTP ${r.status}`);
    const bitmap = await decode(new Uint8Array(await r.arrayBuffer()));
    const { width, height } = bitmap;
    const rgba = pixelsOf(bitmap);
    bitmap.close();
    return { rgba, width, height };
  }
  const rgba = wasm.previewRgba(mix.params, MIX_PRESET_SIDE, MIX_PRESET_SIDE);
  return { rgba, width: MIX_PRESET_SIDE, height: MIX_PRESET_SIDE };
}

// Runs a synthesis job (PyramidSynthesis or SolidSynthesis) one round per macrotask, so that
// Cancel ('cancelPyramid', not queued) gets in between rounds; posts 'pyramidProgress' after
// each and then { type: 'pyramid', cancelled, ...result() } (`result` gives the message's
// fields and its transfer list). Frees the job.
async function runRounds(id, job, t0, result) {
  const mine = { id, cancelled: cancelledSyntheses.delete(id) };
  pyramid = mine;
  try {
    postMessage({ type: 'pyramidProgress', id, done: 0, total: job.steps() });
    let more = job.steps() > 0;
    while (more) {
      await new Promise((r) => setTimeout(r, roundDelayMs));
      if (mine.cancelled) {
        postMessage({ type: 'pyramid', id, cancelled: true });
        return;
      }
      more = job.step();
      postMessage({ type: 'pyramidProgress', id, done: job.done(), total: job.steps() });
    }
    const [fields, transfer] = result();
    postMessage({ type: 'pyramid', id, cancelled: false, ...fields, ms: performance.now() - t0 },
      transfer);
  } finally {
    job.free();
    if (pyramid === mine) pyramid = null;
  }
}

// e2e: milliseconds each synthesis round waits before it runs ('setRoundDelay'; 0 by default),
// so that a test can press Cancel between rounds however fast the machine runs them.
let roundDelayMs = 0;
export function setRoundDelay(ms) {
  roundDelayMs = Math.max(0, Number(ms) || 0);
}

// The running synthesis ({ id, cancelled }), for 'cancelPyramid'; the ids of queued ones
// cancelled before they started.
let pyramid = null;
const cancelledSyntheses = new Set();

// Cancels synthesis `id` ('cancelPyramid', not queued): the running one sees it before its next
// round; a queued one when it starts.
export function cancelSynthesis(id) {
  if (pyramid?.id === id) pyramid.cancelled = true;
  else cancelledSyntheses.add(id);
}
