// The analysis worker's one queue: its jobs (worker.js) and the suggestions' steps
// (suggest.js) run one at a time, in the order they were queued.
let tail = Promise.resolve();

// Queues `step` (sync or async); `onError` takes what it throws.
export function enqueue(step, onError) {
  tail = tail.then(step).catch(onError);
}
