//! Independent work items mapped in parallel on native (rayon), one after another in the
//! browser's worker (no threads there), with results in the items' order either way: callers
//! that reduce them in order get the same answer as a plain loop.

/// `f` of every item of `items`, in order.
pub fn map_in_order<T: Sync, R: Send>(items: &[T], f: impl Fn(&T) -> R + Sync + Send) -> Vec<R> {
    #[cfg(not(target_arch = "wasm32"))]
    {
        use rayon::prelude::*;
        items.par_iter().map(f).collect()
    }
    #[cfg(target_arch = "wasm32")]
    items.iter().map(f).collect()
}

/// `a()` and `b()`, in parallel on native (rayon's work stealing fills one's idle threads with
/// the other's work), one after the other in the browser's worker.
pub fn join<A: Send, B: Send>(
    a: impl FnOnce() -> A + Send,
    b: impl FnOnce() -> B + Send,
) -> (A, B) {
    #[cfg(not(target_arch = "wasm32"))]
    {
        rayon::join(a, b)
    }
    #[cfg(target_arch = "wasm32")]
    (a(), b())
}
