// The analysis worker. It loads the worker's wasm (analyzeRgba, Suggestions, PyramidSynthesis,
// modelStats, previewRgba) and does everything that takes long: decoding a photo file,
// analysing it (or a crop of it), the automatic model choice (retrieval in the pattern
// database, then refinement one start of a model family per step, shared with helper workers
// on machines with more cores: refiner.js), the Heeger–Bergen raster synthesis of the crop
// (one round per step), the model statistics for the plots, and the CPU preview.
//
// Why a worker rather than splitting the work into slices on the UI thread: the expensive steps
// are single calls (the browser's image decode of a 12 MP JPEG, rustfft over the analysis
// image) that cannot be cut into frame-sized pieces without rewriting the analyzer as a state
// machine; in a worker they run whole, in parallel with rendering, and the UI thread only
// receives the params (a few KB) and a preview.
import init, * as wasm from './pkg/proctex_worker.js';

const ready = init();
const PREVIEW_SIDE = 1024; // longest side of the preview sent to the UI (crop panel, split view)
let photo = null; // the current photo: { rgba, width, height, name }

async function decode(bytes) {
  return createImageBitmap(new Blob([bytes]), { imageOrientation: 'from-image' });
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
async function analyseNew(id, name, bitmap, t0, decodeMs, suggest) {
  const rgba = pixelsOf(bitmap);
  const { preview, pw, ph } = previewOf(bitmap);
  const { width, height } = bitmap;
  bitmap.close();
  postMessage({ type: 'progress', id, stage: 'Analysing' });
  const report = wasm.analyzeRgba(rgba, width, height, new Uint32Array(0), 1);
  // `crop` and `seed`: those of the last analysis, for suggestions started on request.
  photo = { rgba, width, height, name, crop: [], seed: 1 };
  postMessage({
    type: 'analysis', id, name, report, ms: performance.now() - t0, decodeMs,
    preview, pw, ph, width, height, suggest,
  }, [preview.buffer]);
  if (suggest) {
    await startSuggestions(id, [], 1);
  } else {
    dropSuggestion(); // the previous photo's refinement is of no use any more
  }
}

// ---- Model suggestions ----
// The pattern database is a file of its own (www/pkg/patterns.ptxdb, a few MB), fetched once.
const dbReady = ready.then(async () => {
  const r = await fetch(new URL('./pkg/patterns.ptxdb', import.meta.url));
  if (!r.ok) throw new Error(`HTTP ${r.status}`);
  return wasm.loadDatabase(new Uint8Array(await r.arrayBuffer()));
});
dbReady.catch(() => {}); // reported per photo, below

// The running suggestion: { job, id, token, cancelled, t0, todo, inflight, waiting, finished,
// helped, helpers, fit, progressDone }. Its work is tasks, shared with helper workers
// (refiner.js; this worker takes `todo` from the front, the helpers from the back; `inflight`:
// tasks at the helpers; `waiting`: this worker waits for them), one per queued step, so that a
// new photo, a crop, the plots' statistics or Cancel get in between:
// `{ kind: 'refine', family, start }`, the starts of the classifier's first three families
// (`pendingStarts()`); once they are in (`finished`), `{ kind: 'order', family }`, the fits whose
// renders order the list (`orderFits()`), while this worker fits the noise model (`ordering`:
// { noise, stored, helped, done }); where the ranking compares the classifier's nearest family's
// render with the noise model's, that family's first round as a fit's tasks (`nearer`) and one
// `{ kind: 'scatter', gen }`; once the list is ranked with a model family as its best,
// `{ kind: 'fit', index, gen }`: the adopted model's final fit (step 6 of the structured fit) in
// rounds (`fitPending()`); `fit`: its state ({ gen, pattern, tasks, helped, done, finish }) until
// `finish` sends its report, with the list for the best row or as 'adopted' for a later pick. A
// pick begins a new fit (a new `gen`); the helpers' replies for an older one are dropped.
let suggestion = null, tokens = 0, fitGens = 0;
// The refinement's time budget (ms from the end of retrieval; 0: none), set by the app: when it
// runs out, the refinement stops as Cancel does (after the start being refined) and ranks.
let refineBudgetMs = 0;

// (Re)arms the time budget of suggestion `s` (the budget may change while it runs).
function armBudget(s) {
  clearTimeout(s.budgetTimer);
  s.budgetTimer = undefined;
  if (refineBudgetMs <= 0 || s.finished || s.cancelled) return;
  s.budgetTimer = setTimeout(() => {
    if (suggestion === s && !s.finished && !s.cancelled) stopRefinement(s, true);
  }, Math.max(0, s.t0 + refineBudgetMs - performance.now()));
}

// Stops the refinement of `s` before its next step (Cancel, or the time budget when
// `timedOut`); if only helpers were refining, ranks now, without their families.
function stopRefinement(s, timedOut) {
  if (s.finished) return; // ranked already (its final fit, if any, is not stopped)
  s.cancelled = true;
  s.timedOut = timedOut;
  if (s.waiting) {
    s.waiting = false;
    scheduleStep(s);
  }
}

// ---- Helper workers: as many as the machine has cores beyond this worker's and the page's
// (at most 3). A helper that fails is retired and its task goes back to `todo`.
const HELPERS = Math.max(0, Math.min(3, (navigator.hardwareConcurrency || 1) - 1));
let helpers = null;
let helperLimit = HELPERS; // e2e/bench: setHelpers
let helperScript = './refiner.js';
function helperPool() {
  if (helpers) return helpers;
  helpers = [];
  for (let k = 0; k < HELPERS; k++) {
    const h = { worker: null, job: null, broken: false, token: 0 };
    try {
      h.worker = new Worker(new URL(helperScript, import.meta.url), { type: 'module' });
    } catch {
      continue;
    }
    h.worker.onmessage = (e) => helperDone(h, e.data);
    h.worker.onerror = () => {
      h.broken = true;
      const job = h.job;
      h.job = null;
      if (job) helperDone(h, { token: job.token, task: job.task, error: 'helper failed' });
    };
    helpers.push(h);
  }
  return helpers;
}

function helperDone(h, m) {
  h.job = null;
  const s = suggestion;
  if (!s) return;
  if (m.token !== s.token) {
    dispatch(s, h); // a superseded job's task is dropped; the helper joins the current job
    return;
  }
  s.inflight--;
  if (m.task.kind === 'scatter' && s.fit?.gen === m.task.gen) s.fit.scattering = false;
  if (m.error) {
    h.broken = true;
    // This worker runs it instead, unless the job has moved past it (a refinement that failed
    // after the ranking is dropped).
    const stillWanted = s.fit
      ? m.task.kind === 'fit' && s.fit.gen === m.task.gen && !s.fit.done
      : m.task.kind === 'order' ? !s.ordering.done : m.task.kind === 'refine' && !s.finished;
    if (stillWanted) s.todo.unshift(m.task);
  } else if (m.task.kind === 'refine' && !s.finished) {
    s.job.setRefinedStart(m.task.family, m.task.start, m.json);
    s.helped++;
    postProgress(s);
  } else if (m.task.kind === 'order' && !s.ordering.done) {
    s.job.setOrderFit(m.task.family, m.json);
    s.ordering.helped++;
  } else if (m.task.kind === 'scatter' && s.fit?.gen === m.task.gen && !s.fit.done) {
    s.job.setNearerScatterings(s.fit.noise, m.both);
    s.fit.scattered = true;
  } else if (m.task.kind === 'fit' && s.fit?.gen === m.task.gen && !s.fit.done) {
    if (m.rgb) s.job.setFitTone(m.task.index, m.rgb);
    else s.job.setFitTask(m.task.index, m.json);
    s.fit.helped++;
  }
  dispatch(s, h);
  // This worker waits only while helpers hold tasks: wake it when the last one is back, a
  // task came back to `todo`, or an ordering fit is in (a cancelled refinement's family may
  // still be out).
  if (s.waiting && (fitInflight(s) === 0 || s.todo.length > 0 || m.task.kind === 'order')) {
    s.waiting = false;
    scheduleStep(s);
  }
}

// Gives helper `h` the next task of `s`, when it is idle and holds the job's photo.
function dispatch(s, h) {
  if (h.broken || h.job || h.token !== s.token || s.todo.length === 0) return;
  if (helpers.indexOf(h) >= helperLimit) return; // e2e/bench: fewer helpers from now on
  if (s.fit ? s.fit.done : s.ordering ? s.ordering.done : s.finished || s.cancelled) return;
  const next = s.todo[s.todo.length - 1];
  if (next.kind === 'fit' && next.tone === undefined && h.fitGen !== next.gen) return;
  const task = s.todo.pop();
  h.job = { token: s.token, task };
  s.inflight++;
  if (task.kind === 'refine') {
    h.worker.postMessage({ type: 'refine', token: s.token, task });
  } else if (task.kind === 'order') {
    h.worker.postMessage({ type: 'order', token: s.token, task, refined: s.job.refinedOf(task.family) });
  } else if (task.kind === 'scatter') {
    s.fit.scattering = true;
    h.worker.postMessage({ type: 'scatter', token: s.token, task, noise: s.fit.noise });
  } else if (task.tone !== undefined) {
    h.worker.postMessage({ type: 'fitTone', token: s.token, task, params: s.fit.best, small: s.fit.nearer });
  } else {
    h.worker.postMessage({
      type: 'fit', token: s.token, task, pattern: s.fit.pattern, chosen: s.job.fitChosen(),
      small: s.fit.nearer,
    });
  }
}

// Sends the job's prepared photo to the helpers that do not hold it yet; they then take tasks.
function engageHelpers(s) {
  const pool = helperPool().filter((h) => !h.broken).slice(0, helperLimit);
  if (pool.length === 0) return;
  s.helpers = Math.max(s.helpers, pool.length);
  let rgb = null, size = null;
  for (const helper of pool) {
    if (helper.token !== s.token) {
      if (!rgb) { size = s.job.preparedSize(); rgb = s.job.preparedPixels(); }
      helper.worker.postMessage({ type: 'photo', token: s.token, rgb, width: size[0], height: size[1], seed: s.seed });
      helper.token = s.token;
    }
    dispatch(s, helper);
  }
}

// Stops and frees the running suggestion job, if any (helpers' replies for it are ignored).
function dropSuggestion() {
  if (suggestion) {
    clearTimeout(suggestion.budgetTimer);
    answerAdoption(suggestion, { superseded: true });
    suggestion.job.free();
  }
  suggestion = null;
}

// Ends the pick being fitted in `s`, if any, with `answer` (superseded, or an error).
function answerAdoption(s, answer) {
  const f = s.fit;
  if (!f || f.done || f.adoption === null) return;
  f.done = true;
  postMessage(answer.error
    ? { type: 'error', id: f.adoption, message: answer.error }
    : { type: 'adopted', id: f.adoption, index: f.index, superseded: true });
}

async function startSuggestions(id, crop, seed) {
  dropSuggestion();
  try {
    await dbReady;
  } catch (e) {
    postMessage({
      type: 'suggestError', id,
      message: 'Model suggestions are unavailable: the pattern database could not be loaded ' +
        `(${e.message ?? e}); the noise model is shown.`,
    });
    return;
  }
  let job;
  try {
    job = new wasm.Suggestions(photo.rgba, photo.width, photo.height, new Uint32Array(crop), seed);
  } catch (e) {
    postMessage({ type: 'suggestError', id, message: `Model suggestions: ${e.message ?? e}` });
    return;
  }
  const s = {
    job, id, seed, token: ++tokens, cancelled: false, timedOut: false, t0: performance.now(),
    todo: [], refineTasks: 0, inflight: 0, finished: false, progressDone: 0,
    waiting: false, helped: 0, helpers: 0, fit: null, ordering: null, orderTasks: 0,
  };
  suggestion = s;
  listRefineTasks(s);
  armBudget(s);
  postMessage({ type: 'suggestProgress', id, done: 0, total: job.steps() });
  if (s.todo.length > 1) engageHelpers(s);
  scheduleStep(s);
}

// Progress when a family is complete: each message repaints the app (without a GPU 0.2-0.3 s).
function postProgress(s) {
  if (s.job.done() === s.progressDone) return;
  s.progressDone = s.job.done();
  postMessage({ type: 'suggestProgress', id: s.id, done: s.progressDone, total: s.job.steps() });
}

// The round's refine tasks in `todo`: a family's starts are tasks of their own (on two cores
// three starts each, not two families); `refineTasks` counts them for the list's message.
function listRefineTasks(s) {
  const p = s.job.pendingStarts();
  s.todo = Array.from({ length: p.length / 2 }, (_, n) => ({ kind: 'refine', family: p[2 * n], start: p[2 * n + 1] }));
  s.refineTasks += s.todo.length;
}

function scheduleStep(s) {
  // A macrotask first, so that messages that arrived meanwhile are queued before the step.
  setTimeout(() => {
    queue = queue.then(() => suggestStep(s)).catch((err) => {
      if (s.fit && !s.fit.done && s.fit.adoption !== null) {
        answerAdoption(s, { error: `Adopting the model: ${err.message ?? err}` });
        return;
      }
      postMessage({ type: 'suggestError', id: s.id, message: `Model suggestions: ${err.message ?? err}` });
    });
  }, 0);
}

// The next round, once every start of the current one is back; idle helpers take theirs at once.
function nextRound(s) {
  listRefineTasks(s);
  if (s.helpers > 0) for (const h of helperPool()) dispatch(s, h);
}

function suggestStep(s) {
  if (suggestion !== s) return; // superseded (and freed)
  if (s.fit) {
    fitStep(s);
    return;
  }
  if (s.ordering) {
    orderStep(s);
    return;
  }
  if (s.finished) return; // already ranked
  if (!s.cancelled && s.todo.length === 0 && s.inflight === 0) nextRound(s);
  if (!s.cancelled && s.todo.length > 0) {
    const { family, start } = s.todo.shift();
    s.job.setRefinedStart(family, start, s.job.refineStart(family, start));
    postProgress(s);
    scheduleStep(s);
    return;
  }
  // Wait for the helpers' last families (their replies wake this up; Cancel ranks now).
  if (s.inflight > 0 && !s.cancelled) {
    s.waiting = true;
    return;
  }
  s.finished = true;
  clearTimeout(s.budgetTimer);
  s.job.settlePartialStarts(); // a stopped refinement's families with some starts in
  s.refinedMs = performance.now() - s.t0;
  // The fits that order the list, in tasks shared with the helpers; the noise model here first.
  s.ordering = { noise: false, stored: 0, helped: 0, done: false };
  s.todo = Array.from(s.job.orderFits(), (family) => ({ kind: 'order', family }));
  s.orderTasks = s.todo.length;
  s.waiting = false;
  engageHelpers(s);
  orderStep(s);
}

// One step of the ordering fits: the noise model, then the families' tasks nobody has taken;
// then, with every family's fit stored, the list.
function orderStep(s) {
  const o = s.ordering;
  if (o.done) return;
  if (!o.noise) {
    s.job.fitNoise();
    o.noise = true;
    scheduleStep(s);
    return;
  }
  if (s.todo.length > 0) {
    const family = s.todo.shift().family;
    s.job.setOrderFit(family, s.job.orderFit(family));
    o.stored++;
    scheduleStep(s);
    return;
  }
  if (o.stored + o.helped < s.orderTasks) {
    s.waiting = true; // a helper's reply wakes it up
    return;
  }
  o.done = true;
  nearerThenRank(s);
}

// Where the ranking will compare the classifier's nearest family's render with the noise
// model's (the nearer-render rule), the first round of that family's final fit runs first, in
// tasks shared with the helpers as a final fit's are (`fit.nearer`: on the ranking's photo),
// and one helper scatters the photo and the noise model's render meanwhile; then the list.
function nearerThenRank(s) {
  const pattern = s.job.nearerPattern();
  if (!pattern) return rankList(s);
  const t0 = performance.now();
  beginFit(s, -1, pattern, null, () => {
    const f = s.fit;
    s.nearer = { ms: performance.now() - t0, tasks: f.tasks, helped: f.helped, scattered: f.scattered };
    [s.fit, s.todo] = [null, []];
    rankList(s);
  }, true);
  fitStep(s);
}

// Ranks the list (every fit that orders it is stored) and begins its best row's final fit.
function rankList(s) {
  const rows = s.job.rank();
  const thumbs = s.job.thumbnails();
  // The best row's final fit, in tasks shared with the helpers (its report goes with the list);
  // the helpers build their own fit of the pattern while this worker builds the job's.
  const pattern = s.job.rowPattern(0);
  if (pattern) {
    beginFit(s, 0, pattern, null, (best) => postSuggestions(s, rows, thumbs, best));
    fitStep(s);
    return;
  }
  postSuggestions(s, rows, thumbs, null);
}

// Begins the final fit of ranked row `index` (its `pattern`, `Suggestions.rowPattern`) in
// tasks; `finish` takes its report. `adoption`: the id of the 'adopt' request it answers (null:
// the list's own best row). The helpers build their own fit of the pattern meanwhile.
// `nearer`: the nearer-render rule's first round instead (`Suggestions.beginNearer`; `finish`
// takes nothing), with the scatterings' task for a helper (the first to take a task).
function beginFit(s, index, pattern, adoption, finish, nearer = false) {
  s.fit = {
    gen: ++fitGens, index, pattern, adoption, finish, tasks: 0, helped: 0, done: false,
    t0: performance.now(), nearer, scattering: false, scattered: false,
    noise: nearer ? s.job.noiseParams() : null,
  };
  s.todo = [];
  s.waiting = false;
  engageHelpers(s);
  const gen = s.fit.gen;
  if (nearer && s.helpers > 0) {
    // A helper scatters while this worker builds its fit (the helpers take from the back of
    // `todo`; each round is listed in front); this worker drops it if no helper took it.
    s.todo.push({ kind: 'scatter', gen });
    for (const h of helperPool()) dispatch(s, h);
  }
  // The other helpers build their own fit meanwhile; the scattering one takes only the tone
  // renders, which need none (`fitGen`: the fit a helper has built).
  for (const h of helperPool()) {
    if (!h.broken && h.token === s.token && h.job?.task.kind !== 'scatter') {
      h.worker.postMessage({ type: 'fitPrepare', token: s.token, pattern, small: nearer });
      h.fitGen = gen;
    }
  }
  if (nearer) s.job.beginNearer();
  else s.job.beginFit(index);
}

// Adopts ranked row `index` of `s` for request `id`: a structured row's final fit in tasks
// shared with the helpers, answered with 'adopted' when its last task is in. An earlier pick
// still being fitted is superseded whatever this one is. Returns false when this one cannot
// run in tasks (the noise model's row, whose fit is one quick analysis; or the list's own fit
// still running), for the caller to fit it in one piece.
function adoptInTasks(s, id, index) {
  answerAdoption(s, { superseded: true });
  if (!s.finished || (s.fit && !s.fit.done)) return false;
  const pattern = s.job.rowPattern(index);
  if (!pattern) return false;
  beginFit(s, index, pattern, id, (report) => {
    const f = s.fit;
    postMessage({
      type: 'adopted', id, index, report, ms: performance.now() - f.t0, fitTasks: f.tasks,
      fitHelped: f.helped, helpers: Math.min(helperLimit, helperPool().filter((h) => !h.broken).length),
    });
  });
  scheduleStep(s);
  return true;
}

// The final fit's tasks in flight at the helpers (every task but the scatterings').
function fitInflight(s) {
  return s.inflight - (s.fit?.scattering ? 1 : 0);
}

// Lists the final fit's next round in front of `todo` (where the scatterings' task may wait).
// Rounds: the residual's amplitudes, the rougher variants, then the renders that the best fit's
// tone curve pools (`tone`: their tasks travel as pixels, not JSON).
function listFitRound(s) {
  const scored = s.job.fitScoredTasks();
  const gen = s.fit.gen;
  const round = Array.from(s.job.fitPending(), (index) => (index >= scored
    ? { kind: 'fit', index, gen, tone: index - scored } : { kind: 'fit', index, gen }));
  if (round.length === 0) return;
  if (round.some((t) => t.tone !== undefined)) s.fit.best = s.job.fitBestParams();
  s.fit.tasks += round.length;
  s.todo = round.concat(s.todo);
  for (const h of helperPool()) dispatch(s, h);
}

// One task of the final fit per queued step (a new photo supersedes it between steps; Cancel
// does not stop it: the list is ranked by then); the report and the list go out at the end.
function fitStep(s) {
  if (s.fit.done) return;
  if (fitInflight(s) === 0 && !s.todo.some((t) => t.kind === 'fit')) listFitRound(s);
  if (s.todo.length > 0) {
    const task = s.todo.shift();
    // (A scatterings' task that no helper took is dropped: the ranking scatters.)
    if (task.tone !== undefined) s.job.setFitTone(task.index, s.job.fitTone(task.index));
    else if (task.kind === 'fit') s.job.setFitTask(task.index, s.job.fitTask(task.index));
    scheduleStep(s);
    return;
  }
  if (s.inflight > 0) {
    s.waiting = true; // a helper's reply wakes it up
    return;
  }
  if (s.fit.nearer) {
    s.job.finishNearer();
    s.fit.done = true;
    s.fit.finish();
    return;
  }
  const report = s.job.fitReport(); // before `done`: an error here answers a pick's request
  s.fit.done = true;
  s.fit.finish(report);
}

function postSuggestions(s, rows, thumbs, best) {
  postMessage({
    type: 'suggestions', id: s.id, rows, thumbs, best, cancelled: s.cancelled, timedOut: s.timedOut,
    ms: performance.now() - s.t0, refinedMs: s.refinedMs, helpers: s.helpers, helped: s.helped,
    refineTasks: s.refineTasks, fitTasks: s.fit?.tasks ?? 0, fitHelped: s.fit?.helped ?? 0,
    orderTasks: s.orderTasks, orderHelped: s.ordering?.helped ?? 0,
    nearer: s.nearer ?? null,
  }, [thumbs.buffer]);
  fitRows(s);
}

// The rows the ranking did not fit (the list's order does not depend on them), one per macrotask
// so that a new photo, a crop or a click is not kept waiting; their distances and thumbnails.
function fitRows(s) {
  setTimeout(() => {
    queue = queue.then(() => {
      if (suggestion !== s) return; // superseded (and freed)
      const i = s.job.fitNext();
      if (i < 0) return;
      const thumb = s.job.thumbnail(i);
      const last = s.job.unfitted() === 0;
      postMessage({
        type: 'suggestionFitted', id: s.id, index: i, row: s.job.row(i), thumb, last,
        ms: performance.now() - s.t0,
      }, [thumb.buffer]);
      if (!last) fitRows(s);
    }).catch((err) => {
      postMessage({ type: 'suggestError', id: s.id, message: `Model suggestions: ${err.message ?? err}` });
    });
  }, 0);
}

// Benchmarks: the median milliseconds of `reps` calls of `f`.
function medianMs(reps, f) {
  const t = [];
  for (let i = 0; i < reps; i++) {
    const s = performance.now();
    f();
    t.push(performance.now() - s);
  }
  t.sort((a, b) => a - b);
  return t[t.length >> 1];
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
        await analyseNew(m.id, m.name, bitmap, t0, 0, true);
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
      photo.crop = m.crop;
      photo.seed = m.seed;
      postMessage({ type: 'analysis', id: m.id, name: photo.name, report, ms: performance.now() - t0 });
      await startSuggestions(m.id, m.crop, m.seed);
      return;
    }
    case 'suggest': {
      // Suggestions asked for by the user (the start-up sample gets none by itself).
      if (!photo) throw new Error('no photo to suggest models for');
      postMessage({ type: 'suggesting', id: m.id });
      await startSuggestions(m.id, photo.crop, photo.seed);
      return;
    }
    case 'adopt': {
      if (!suggestion) throw new Error('no suggestions to adopt');
      // Not awaited: the fit's tasks are steps of this same queue.
      if (adoptInTasks(suggestion, m.id, m.index)) return;
      const report = suggestion.job.report(m.index);
      postMessage({ type: 'adopted', id: m.id, index: m.index, report, ms: performance.now() - t0 });
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
    case 'pyramid': {
      // The Heeger–Bergen synthesis of the current photo's crop, or of A (a shipped sample or a
      // preset's texture, whole).
      let a;
      if (m.a) a = { ...(await mixtureSource(m.a)), crop: new Uint32Array(0) };
      else if (photo) a = { ...photo, crop: new Uint32Array(m.crop) };
      else throw new Error('no photo to synthesise from');
      let job;
      if (m.mix) {
        // A texture mixture with B: a shipped sample photo or a preset's texture.
        const b = await mixtureSource(m.mix);
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

// A texture of a mixture: a shipped sample photo ({ sample: name }), a preset's texture
// ({ params: json }, rendered on the CPU at 256²) or the current photo's crop ({ crop: [x, y,
// w, h] }), as RGBA.
const MIX_PRESET_SIDE = 256;
async function mixtureSource(mix) {
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

// The running synthesis ({ id, cancelled }), for 'cancelPyramid'; the ids of queued ones
// cancelled before they started.
let pyramid = null;
const cancelledSyntheses = new Set();

// Jobs run one at a time, in order.
let queue = Promise.resolve();
onmessage = (e) => {
  const m = e.data;
  if (m.type === 'setHelpers') {
    helperLimit = m.n;
    if (m.script && m.script !== helperScript) {
      // Tests: another helper script (a missing one, to see the fallback); a fresh pool.
      for (const h of helpers ?? []) h.worker?.terminate();
      helpers = null;
      helperScript = m.script;
    }
    return;
  }
  if (m.type === 'setRefineBudget') {
    refineBudgetMs = Math.max(0, Number(m.seconds) || 0) * 1000;
    if (suggestion) armBudget(suggestion);
    return;
  }
  if (m.type === 'setRoundDelay') {
    roundDelayMs = Math.max(0, Number(m.ms) || 0);
    return;
  }
  if (m.type === 'cancelPyramid') {
    // Not queued: the running synthesis `m.id` sees it before its next round; a queued one
    // when it starts.
    if (pyramid?.id === m.id) pyramid.cancelled = true;
    else cancelledSyntheses.add(m.id);
    return;
  }
  if (m.type === 'cancelSuggest') {
    // Not queued: the running refinement sees it before its next step.
    if (suggestion && !suggestion.cancelled) stopRefinement(suggestion, false);
    return;
  }
  queue = queue.then(() => handle(m)).catch((err) => {
    postMessage({ type: 'error', id: m.id, message: String(err && err.message ? err.message : err) });
  });
};
