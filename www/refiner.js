// A helper of the analysis worker (worker.js starts up to three): it refines model families
// of the current suggestion job in parallel with the analysis worker, one start of a family
// per message, then fits the families whose renders order the list, then runs tasks of the
// nearer-render rule's first round (on the ranking's photo: `small`) and scatters for it, then
// tasks of the adopted model's final fit the same way. It loads the same wasm and pattern
// database, rebuilds the job's retrieval from the job's prepared photo and seed
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

let current = null; // { token, refiner }

onmessage = async (e) => {
  const m = e.data;
  try {
    await ready;
    if (m.type === 'photo') {
      if (current) current.refiner.free();
      current = null;
      current = { token: m.token, refiner: new wasm.Refiner(m.rgb, m.width, m.height, m.seed) };
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
    if (['refine', 'order', 'fit', 'fitTone', 'scatter'].includes(m.type)) {
      postMessage({ token: m.token, task: m.task, error: String(err.message ?? err) });
    }
  }
};
