// A helper of the analysis worker (worker.js starts up to three): it refines model families
// of the current suggestion job in parallel with the analysis worker, one family per message.
// It loads the same wasm and pattern database, rebuilds the job's retrieval from the job's
// prepared photo and seed (`Refiner`), and returns each family's result as JSON, which the
// analysis worker stores with `Suggestions.setRefined`: the same numbers as refining there.
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
    if (m.type === 'refine') {
      if (!current || current.token !== m.token) throw new Error('no photo for this job');
      const json = current.refiner.refine(m.family);
      postMessage({ token: m.token, family: m.family, json });
    }
  } catch (err) {
    if (m.type === 'refine') {
      postMessage({ token: m.token, family: m.family, error: String(err.message ?? err) });
    }
  }
};
