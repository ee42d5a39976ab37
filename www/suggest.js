// The analysis worker's model suggestions (worker.js runs them on its job queue): retrieval in
// the pattern database, the refinement one start of a model family per queued step, the fits
// that order the list, the nearer-render rule's first round, the ranking and the adopted
// model's final fit, each in tasks shared with helper workers (refiner.js) on machines with
// more cores; the list, its thumbnails and the adopted fit go to the page as messages.
import * as wasm from './pkg/proctex_worker.js';
import { enqueue } from './queue.js';

// The pattern database is a file of its own (www/pkg/patterns.ptxdb, a few MB), fetched once
// the worker's wasm is `ready`; a failure is reported with each photo's suggestions.
let dbReady = null;
export function loadPatternDatabase(ready) {
  dbReady = ready.then(async () => {
    const r = await fetch(new URL('./pkg/patterns.ptxdb', import.meta.url));
    if (!r.ok) throw new Error(`HTTP ${r.status}`);
    return wasm.loadDatabase(new Uint8Array(await r.arrayBuffer()));
  });
  dbReady.catch(() => {});
  return dbReady;
}

// The running suggestion: { job, id, token, cancelled, t0, todo, inflight, waiting, finished,
// helped, helpers, fit, progressDone, stored, noiseFitted }. Its work is tasks, shared with
// helper workers (refiner.js; this worker takes `todo` from the front, the helpers from the back,
// but for the starts that the first helper refines ahead, below; `inflight`: tasks at the
// helpers; `waiting`: this worker waits for them), one per queued step, so that a new photo, a
// crop, the plots' statistics or Cancel get in between: `{ kind: 'refine', family, start }`, the
// starts of the classifier's first three families (`pendingStarts()`); once they are in
// (`finished`), `{ kind: 'order', family }`, the fits whose renders order the list
// (`orderFits()`), while this worker fits the noise model unless it did before its starts
// (`ordering`: { noise, stored, helped, done }); where the ranking compares the classifier's
// nearest family's render with the noise model's, that family's first round as a fit's tasks
// (`nearer`) and one `{ kind: 'scatter', gen }`; once the list is ranked with a model family as
// its best, `{ kind: 'fit', index, gen }`: the adopted model's final fit (step 6 of the structured fit) in
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
  aheadHelper(s)?.worker.postMessage({ type: 'stopAhead', token: s.token });
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
    const h = { worker: null, jobs: [], broken: false, token: 0 };
    try {
      h.worker = new Worker(new URL(helperScript, import.meta.url), { type: 'module' });
    } catch {
      continue;
    }
    h.worker.onmessage = (e) => helperDone(h, e.data);
    h.worker.onerror = () => {
      h.broken = true;
      if (h.ahead && !h.ahead.done) aheadMessage(h, { token: h.ahead.token, aheadDone: true, error: true });
      for (const job of h.jobs.slice()) helperDone(h, { token: job.token, task: job.task, error: 'helper failed' });
    };
    helpers.push(h);
  }
  return helpers;
}

function helperDone(h, m) {
  if (m.claim || m.ahead || m.aheadDone) {
    aheadMessage(h, m);
    return;
  }
  h.jobs.shift(); // a helper answers its tasks in the order it got them
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
    storeStart(s, m.task, m.json);
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
  wake(s, m.task.kind === 'order');
}

// Wakes this worker, which waits only while helpers hold tasks, when the last one is back, a task
// came back to `todo`, or an ordering fit is in (`orderIn`: a cancelled start may be out).
function wake(s, orderIn = false) {
  if (s.waiting && (fitInflight(s) === 0 || s.todo.length > 0 || orderIn)) {
    s.waiting = false;
    scheduleStep(s);
  }
}

// ---- The first helper refines ahead ----
// While this worker fits the noise model of a new photo or crop, and retrieves, it hands out no
// task. So the helpers get the job's photo first (`sendAhead`) and retrieve meanwhile, and the
// first (`h.ahead`: { token, claims, done }) refines starts from the front of the list on its own
// (refiner.js), naming each ({ claim }) before it refines it; this worker takes starts from the
// back and names each taken here or by other helpers ('taken'). Where the two meet both may
// refine one start: the same numbers, stored once (`s.stored`).
const startKey = (t) => `${t.family}.${t.start}`;

// Sends the photo of the suggestion job about to start (`request` of `photo`, as
// `startSuggestions` takes them) to the helpers; the job's token, or null (no helpers, a crop
// the analysis will refuse, or a region of more than AHEAD_PIXELS: making the job's photo
// delays the noise model by about 12 ms a megapixel, a 24 MP JPEG's by 0.3 s). The helpers get
// the analysis-size photo, its lighting already divided out where the request says.
const AHEAD_PIXELS = 4e6;
export function sendAhead({ rgba, width, height }, { crop, seed, flatten }) {
  if ((crop.length ? crop[2] * crop[3] : width * height) > AHEAD_PIXELS) return null;
  const pool = helperPool().filter((h) => !h.broken).slice(0, helperLimit);
  if (pool.length === 0) return null;
  let p;
  try {
    p = new wasm.SuggestionPhoto(rgba, width, height, new Uint32Array(crop), seed, flatten);
  } catch {
    return null;
  }
  const [rgb, size] = [p.pixels(), p.size()];
  p.free();
  const token = ++tokens;
  pool.forEach((h, k) => {
    h.worker.postMessage({ type: 'photo', token, rgb, width: size[0], height: size[1], seed, ahead: k === 0 });
    h.token = token;
    h.ahead = k === 0 ? { token, claims: new Map(), done: false } : null;
  });
  return token;
}

// The helper refining ahead for `s`, if one still is.
function aheadHelper(s) {
  return helperPool().find((h) => h.ahead?.token === s.token && !h.ahead.done);
}

// Names a start taken here or by another helper to the helper refining ahead.
function tellTaken(s, task) {
  const h = aheadHelper(s);
  if (h) h.worker.postMessage({ type: 'taken', token: s.token, family: task.family, start: task.start });
}

// Stores a refined start unless it is in already (the helper refining ahead may meet this one).
function storeStart(s, task, json) {
  const key = startKey(task);
  if (s.stored.has(key)) return;
  s.stored.add(key);
  s.job.setRefinedStart(task.family, task.start, json);
}

// A claim, a result or the end of the helper refining ahead. Before its job exists (the
// database still loading) claims and results wait in `h.ahead.claims` for `startSuggestions`.
function aheadMessage(h, m) {
  const a = h.ahead;
  if (!a || a.token !== m.token) return;
  const s = suggestion?.token === m.token ? suggestion : null;
  if (m.claim) {
    const c = { key: startKey(m.claim), task: m.claim, counted: false, json: undefined };
    a.claims.set(c.key, c);
    if (s) aheadClaim(s, c);
  } else if (m.aheadDone) {
    a.done = true;
    if (m.error) h.broken = true; // its unanswered starts go back to `todo`
    for (const c of a.claims.values()) {
      if (s && c.counted && c.json === undefined) {
        c.counted = false;
        s.inflight--;
        if (!s.finished && !s.stored.has(c.key)) s.todo.push(c.task);
      }
    }
  } else {
    const c = a.claims.get(startKey(m.task));
    if (!c) return;
    c.json = m.json;
    if (s) aheadClaim(s, c);
  }
  if (s) {
    dispatch(s, h);
    wake(s);
  }
}

// A start the helper refining ahead took: out of `todo`, in flight until its result is in.
function aheadClaim(s, c) {
  s.todo = s.todo.filter((t) => startKey(t) !== c.key);
  if (c.json === undefined) {
    if (!c.counted) s.inflight++;
    c.counted = true;
    return;
  }
  if (c.counted) s.inflight--;
  c.counted = false;
  if (s.finished || s.stored.has(c.key)) return;
  storeStart(s, c.task, c.json);
  s.helped++;
  postProgress(s);
}

// Gives helper `h` the next task of `s`, when it holds fewer than `queue` tasks (1: when it is
// idle) and holds the job's photo.
function dispatch(s, h, queue = 1) {
  if (h.broken || h.token !== s.token || s.todo.length === 0 || h.jobs.length >= queue) return;
  if (helpers.indexOf(h) >= helperLimit) return; // e2e/bench: fewer helpers from now on
  if (h.ahead?.token === s.token && !h.ahead.done) return; // it takes its own starts
  if (s.fit ? s.fit.done : s.ordering ? s.ordering.done : s.finished || s.cancelled) return;
  const next = s.todo[s.todo.length - 1];
  if (next.kind === 'fit' && next.tone === undefined && h.fitGen !== next.gen) return;
  const task = s.todo.pop();
  h.jobs.push({ token: s.token, task });
  s.inflight++;
  if (task.kind === 'refine') {
    tellTaken(s, task);
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
  dispatch(s, h, queue);
}

// Sends the job's prepared photo to the helpers that do not hold it yet; they then take tasks:
// two each where the fits that order the list begin while this worker fits the noise model (a
// long step, after which it could hand out a second only late).
function engageHelpers(s) {
  const queue = s.ordering && !s.ordering.noise ? 2 : 1;
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
    dispatch(s, helper, queue);
  }
}

// Stops and frees the running suggestion job, if any (helpers' replies for it are ignored).
export function dropSuggestion() {
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

// Ranks models for `photo` (the worker's current photo: { rgba, width, height }) analysed as
// `request` says ({ crop, seed, flatten }: `analyzeRgba`'s crop, seed and lighting option).
// `aheadToken`: the token that `sendAhead` gave the helpers for this job (null: none);
// `requestT0`: when the photo or crop was asked for (the list's `requestMs`); `report`: its
// analysis (`analyzeRgba`), which the ranking's noise fit takes where it is the same analysis.
export async function startSuggestions(photo, id, request, aheadToken, requestT0, report = null) {
  const { crop, seed, flatten } = request;
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
    job = new wasm.Suggestions(photo.rgba, photo.width, photo.height, new Uint32Array(crop), seed,
      flatten);
  } catch (e) {
    postMessage({ type: 'suggestError', id, message: `Model suggestions: ${e.message ?? e}` });
    return;
  }
  const s = {
    job, id, seed, token: aheadToken ?? ++tokens, cancelled: false, timedOut: false,
    t0: performance.now(), requestT0, todo: [], refineTasks: 0, inflight: 0, finished: false,
    progressDone: 0, stored: new Set(), report,
    waiting: false, helped: 0, helpers: 0, fit: null, ordering: null, orderTasks: 0,
  };
  suggestion = s;
  listRefineTasks(s);
  for (const h of helperPool()) {
    if (h.ahead?.token !== s.token) continue;
    // (A start that a failed helper took and did not return stays in `todo`.)
    for (const c of h.ahead.claims.values()) if (!h.ahead.done || c.json !== undefined) aheadClaim(s, c);
  }
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
    enqueue(() => suggestStep(s), (err) => {
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
  if (!s.cancelled && s.todo.length > 0 && !s.noiseFitted && aheadHelper(s)) {
    // While a helper refines ahead (it needs no task from here), the noise model's fit for the
    // ranking first (it does not depend on the refinement): the fits that order the list then
    // start without this step, during which the helpers would wait for their tasks.
    fitNoiseModel(s);
    scheduleStep(s);
    return;
  }
  if (!s.cancelled && s.todo.length > 0) {
    // From the back while a helper refines ahead from the front.
    const task = aheadHelper(s) ? s.todo.pop() : s.todo.shift();
    tellTaken(s, task);
    storeStart(s, task, s.job.refineStart(task.family, task.start));
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
  s.ordering = { noise: !!s.noiseFitted, stored: 0, helped: 0, done: false };
  s.todo = Array.from(s.job.orderFits(), (family) => ({ kind: 'order', family }));
  s.orderTasks = s.todo.length;
  s.waiting = false;
  engageHelpers(s);
  orderStep(s);
}

// The noise model's fit for the ranking: from the analysis the app shows where that is the
// ranking's own (a photo of at most 256² pixels: it is only scored), else fitted.
function fitNoiseModel(s) {
  if (!(s.report && s.job.setNoiseAnalysis(s.report))) s.job.fitNoise();
  s.noiseFitted = true;
}

// One step of the ordering fits: the noise model, then the families' tasks nobody has taken;
// then, with every family's fit stored, the list.
function orderStep(s) {
  const o = s.ordering;
  if (o.done) return;
  if (!o.noise) {
    fitNoiseModel(s);
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
  if (!pattern) return rankAndAdopt(s);
  const t0 = performance.now();
  beginFit(s, -1, pattern, null, () => {
    const f = s.fit;
    s.nearer = { ms: performance.now() - t0, tasks: f.tasks, helped: f.helped, scattered: f.scattered };
    [s.fit, s.todo] = [null, []];
    rankAndAdopt(s);
  }, true);
  fitStep(s);
}

// Ranks the list and sends it with its first row's final fit (tasks shared with the helpers). A
// family over the speck limit at every fit is passed over for the next row of the top three that
// is not (its final fit; the noise model's render checked), moved to the front; none: the first
// row as ranked (`first`: its report). The native choice, bit for bit (`retrieve::adopt`).
function rankAndAdopt(s, rows = s.job.rank(), j = 0, first = null) {
  const post = (i, report) => postSuggestions(s, i > 0 ? s.job.promote(i) : rows, s.job.thumbnails(), report);
  if (j >= s.job.speckCleanRows()) return post(0, first);
  const pattern = s.job.rowPattern(j);
  if (!pattern) {
    if (j === 0 || s.job.noiseSpeckClean(s.report ?? '')) post(j, null);
    else rankAndAdopt(s, rows, j + 1, first);
    return;
  }
  beginFit(s, j, pattern, null, (report) => {
    if (s.job.fitSpeckClean()) post(j, report);
    else rankAndAdopt(s, rows, j + 1, j === 0 ? report : first);
  });
  fitStep(s);
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
    if (!h.broken && h.token === s.token && !h.jobs.some((j) => j.task.kind === 'scatter')) {
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
    requestMs: s.requestT0 === undefined ? null : performance.now() - s.requestT0,
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
    enqueue(() => {
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
    }, (err) => {
      postMessage({ type: 'suggestError', id: s.id, message: `Model suggestions: ${err.message ?? err}` });
    });
  }, 0);
}

// ---- What the worker's messages ask of the suggestions ----

// The refinement's time budget (seconds; 0: none), for the running refinement too.
export function setRefineBudget(seconds) {
  refineBudgetMs = Math.max(0, Number(seconds) || 0) * 1000;
  if (suggestion) armBudget(suggestion);
}

// e2e/bench: at most `n` helpers from now on; `script`: another helper script (tests: a missing
// one, to see the fallback), in a fresh pool.
export function setHelpers(n, script) {
  helperLimit = n;
  if (script && script !== helperScript) {
    for (const h of helpers ?? []) h.worker?.terminate();
    helpers = null;
    helperScript = script;
  }
}

// Cancel: the running refinement stops before its next step and the list is ranked.
export function cancelSuggestions() {
  if (suggestion && !suggestion.cancelled) stopRefinement(suggestion, false);
}

// Adopts ranked row `index` for request `id` (`t0`: when it came): in tasks where it can run
// so, else fitted in one piece here and answered at once.
export function adoptSuggestion(id, index, t0) {
  if (!suggestion) throw new Error('no suggestions to adopt');
  // Not awaited: the fit's tasks are steps of this same queue.
  if (adoptInTasks(suggestion, id, index)) return;
  const report = suggestion.job.report(index);
  postMessage({ type: 'adopted', id, index, report, ms: performance.now() - t0 });
}
