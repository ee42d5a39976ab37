//! What the benchmarks share: a median of repeated timings, in milliseconds.

use std::time::{Duration, Instant};

/// The median time of `reps` runs of `f`, after one warm-up run (FFT plans, caches).
pub fn median_time(reps: usize, mut f: impl FnMut()) -> Duration {
    f();
    let mut t: Vec<Duration> = (0..reps)
        .map(|_| {
            let s = Instant::now();
            f();
            s.elapsed()
        })
        .collect();
    t.sort();
    t[reps / 2]
}

/// Milliseconds.
pub fn ms(d: Duration) -> f64 {
    d.as_secs_f64() * 1e3
}
