// A helper of the analysis worker (worker.js starts up to three): it refines model families
// of the current suggestion job in parallel with the analysis worker, one start of a family
// per message (the first helper also on its own, from the front of the list, while the worker
// fits the noise model: `refineAhead`), then fits the families whose renders order the list,
// then runs tasks of the nearer-render rule's first round (on the ranking's photo: `small`) and
// scatters for it, then tasks of the adopted model's final fit the same way. It loads the same
// wasm and pattern database, rebuilds the job's retrieval from the job's prepared photo and seed
// (`Refiner`), and returns each result (a refinement, a family's fit or a scored fit as JSON,
// a tone render as pixels), which the analysis worker stores with `Suggestions.setRefinedStart`,
// `setOrderFit`, `setFitTask` or `setFitTone`: the same numbers as running it there.
import init, * as wasm from './pkg/proctex_worker.js';

const ready = init().then(async () => {
  const r = await fetch(new URL('./pkg/patterns.ptxdb', import.meta.url));
  if (!r.ok) throw new Error(`the pattern database: HTTP ${r.status}`);
  wasm.loadDatabase(new Uint8Array(await r.arrayBuffer()));
});
ready.catch(() => {}); // reported with each refine request, below

let current = null; // { token, refiner, taken, stopped }

// Refines the starts of `job`'s list from the front, on its own, until they are all taken (here,
// or by the analysis worker and its other helpers: 'taken'), the photo changes or the worker
// stops it ('stopAhead'): names each start ({ claim }) before refining it, then returns it as a
// task's result. Between starts the messages that came meanwhile are read.
async function refineAhead(job) {
  const p = job.refiner.pendingStarts();
  try {
    for (let n = 0; n < p.length / 2; n++) {
      await new Promise((r) => setTimeout(r, 0));
      if (current !== job || job.stopped) break;
      const task = { kind: 'refine', family: p[2 * n], start: p[2 * n + 1] };
      if (job.taken.has(`${task.family}.${task.start}`)) continue;
      postMessage({ token: job.token, claim: task });
      const json = job.refiner.refineStart(task.family, task.start);
      postMessage({ token: job.token, task, json, ahead: true });
    }
    postMessage({ token: job.token, aheadDone: true });
  } catch {
    postMessage({ token: job.token, aheadDone: true, error: true });
  }
}

onmessage = async (e) => {
  const m = e.data;
  try {
    await ready;
    if (m.type === 'photo') {
      if (current) current.refiner.free();
      current = null;
      const refiner = new wasm.Refiner(m.rgb, m.width, m.height, m.seed);
      current = { token: m.token, refiner, taken: new Set(), stopped: false };
      if (m.ahead) refineAhead(current);
      return;
    }
    if (m.type === 'taken' || m.type === 'stopAhead') {
      if (current?.token !== m.token) return;
      if (m.type === 'taken') current.taken.add(`${m.family}.${m.start}`);
      else current.stopped = true;
      return;
    }
    if (m.type === 'fitPrepare') {
      // Errors surface with the first task of this fit, which prepares it again.
      if (current && current.token === m.token) {
        try { current.refiner.fitPrepare(m.pattern, !!m.small); } catch { /* see above */ }
      }
      return;
    }
    if (!current || current.token !== m.token) throw new Error('no photo for this job');
    if (m.type === 'fitTone') {
      const rgb = current.refiner.fitTone(m.params, m.task.tone, !!m.small);
      postMessage({ token: m.token, task: m.task, rgb }, [rgb.buffer]);
    } else if (m.type === 'scatter') {
      const both = current.refiner.nearerScatterings(m.noise);
      postMessage({ token: m.token, task: m.task, both }, [both.buffer]);
    } else if (m.type === 'refine' || m.type === 'order' || m.type === 'fit') {
      let json;
      if (m.type === 'refine') json = current.refiner.refineStart(m.task.family, m.task.start);
      else if (m.type === 'order') json = current.refiner.orderFit(m.task.family, m.refined);
      else json = current.refiner.fitTask(m.pattern, m.task.index, m.chosen, !!m.small);
      postMessage({ token: m.token, task: m.task, json });
    }
  } catch (err) {
    // A photo that fails: the first task's request reports it; the worker stops waiting for
    // starts refined ahead.
    if (m.type === 'photo' && m.ahead) postMessage({ token: m.token, aheadDone: true, error: true });
    if (['refine', 'order', 'fit', 'fitTone', 'scatter'].includes(m.type)) {
      postMessage({ token: m.token, task: m.task, error: String(err.message ?? err) });
    }
  }
};
