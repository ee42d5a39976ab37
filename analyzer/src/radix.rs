//! Sorting of `f32` by `f32::total_cmp` in linear time: least-significant-digit radix sort of
//! the values' bits mapped to an unsigned key of the same order (three passes of 11 bits).
//!
//! Why: the analysis sorts whole images many times (the colour distance's 13 projections of
//! 65,536 pixels per scored candidate, the rank pairing of the structured fit, the descriptor's
//! quantiles); a comparison sort of 65,536 floats took about a tenth of a native analysis
//! (perf, brick sample). The order is `total_cmp`'s exactly, so every result is the same bits
//! as with `sort_unstable_by(f32::total_cmp)` (equal keys are equal bit patterns, so an
//! unstable sort cannot order them differently), and [`argsort`] is stable.

/// The unsigned key whose order is `f32::total_cmp`'s: negative values have every bit
/// flipped, the others their sign bit.
#[inline]
fn key(v: f32) -> u32 {
    let b = v.to_bits();
    b ^ (((b as i32) >> 31) as u32 | 0x8000_0000)
}

const BITS: u32 = 11;
const BUCKETS: usize = 1 << BITS;
const PASSES: u32 = 3;

/// Each pass's digit counts, all from one read of `keys` (the passes move keys, not change
/// them, so every pass's counts are known before the first).
fn digit_counts(keys: &[u32]) -> Vec<[usize; BUCKETS]> {
    let mut counts = vec![[0usize; BUCKETS]; PASSES as usize];
    for &k in keys {
        for (p, c) in counts.iter_mut().enumerate() {
            c[((k >> (p as u32 * BITS)) as usize) & (BUCKETS - 1)] += 1;
        }
    }
    counts
}

/// One stable counting pass of `keys` (with `items` alongside) on digit `pass`, whose counts
/// are `count`, into `keys_out` and `items_out`.
fn pass<T: Copy>(
    keys: &[u32],
    items: &[T],
    keys_out: &mut [u32],
    items_out: &mut [T],
    pass: u32,
    count: &[usize; BUCKETS],
) {
    let shift = pass * BITS;
    let digit = |k: u32| ((k >> shift) as usize) & (BUCKETS - 1);
    let mut start = [0usize; BUCKETS];
    let mut sum = 0;
    for (s, &c) in start.iter_mut().zip(count) {
        *s = sum;
        sum += c;
    }
    for (&k, &item) in keys.iter().zip(items) {
        let d = digit(k);
        keys_out[start[d]] = k;
        items_out[start[d]] = item;
        start[d] += 1;
    }
}

/// Sorts `keys` stably, carrying `items`. A pass whose digit is the same in every key would
/// leave the order as it is, and is skipped: the top digit (sign, exponent) often is, for the
/// values of one image.
fn sort_keyed<T: Copy + Default>(mut keys: Vec<u32>, mut items: Vec<T>) -> (Vec<u32>, Vec<T>) {
    let n = keys.len();
    let counts = digit_counts(&keys);
    let (mut keys2, mut items2) = (Vec::new(), Vec::new());
    for p in 0..PASSES {
        let count = &counts[p as usize];
        if count.contains(&n) {
            continue;
        }
        if keys2.len() != n {
            (keys2, items2) = (vec![0u32; n], vec![T::default(); n]);
        }
        pass(&keys, &items, &mut keys2, &mut items2, p, count);
        std::mem::swap(&mut keys, &mut keys2);
        std::mem::swap(&mut items, &mut items2);
    }
    (keys, items)
}

/// Below this length a comparison sort is as fast (the passes' bucket arrays dominate).
const SMALL: usize = 512;

/// Sorts `v` in `f32::total_cmp` order.
pub fn sort(v: &mut [f32]) {
    if v.len() < SMALL {
        v.sort_unstable_by(f32::total_cmp);
        return;
    }
    let keys: Vec<u32> = v.iter().map(|&x| key(x)).collect();
    let (sorted, _) = sort_keyed(keys, vec![(); v.len()]);
    for (out, k) in v.iter_mut().zip(sorted) {
        // The inverse of `key`: the sign bit set means the value was not negative.
        let b = if k & 0x8000_0000 != 0 {
            k ^ 0x8000_0000
        } else {
            !k
        };
        *out = f32::from_bits(b);
    }
}

/// The indices of `v` in `f32::total_cmp` order of their values, equal values in index order
/// (what `sort_by(|a, b| v[a].total_cmp(&v[b]).then(a.cmp(b)))` gives).
pub fn argsort(v: &[f32]) -> Vec<u32> {
    let idx: Vec<u32> = (0..v.len() as u32).collect();
    if v.len() < SMALL {
        let mut idx = idx;
        idx.sort_by(|&a, &b| v[a as usize].total_cmp(&v[b as usize]).then(a.cmp(&b)));
        return idx;
    }
    let keys: Vec<u32> = v.iter().map(|&x| key(x)).collect();
    sort_keyed(keys, idx).1
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng;

    fn values(n: usize) -> Vec<f32> {
        let special = [
            0.0,
            -0.0,
            1.0,
            -1.0,
            f32::INFINITY,
            f32::NEG_INFINITY,
            1e-40,
            -1e-40,
        ];
        (0..n)
            .map(|i| {
                if i % 97 == 0 {
                    special[(i / 97) % special.len()]
                } else {
                    // Repeats on purpose: ties must come out as a comparison sort puts them.
                    let u = rng::uniform(7, 0, (i % 5000) as u32) as f32;
                    (u - 0.4) * 1e3
                }
            })
            .collect()
    }

    #[test]
    fn sort_gives_total_cmp_order_bit_for_bit() {
        for n in [0, 1, 7, 511, 512, 4096, 65_536] {
            let v = values(n);
            let mut a = v.clone();
            let mut b = v.clone();
            sort(&mut a);
            b.sort_unstable_by(f32::total_cmp);
            let bits = |x: &[f32]| x.iter().map(|f| f.to_bits()).collect::<Vec<_>>();
            assert_eq!(bits(&a), bits(&b), "length {n}");
        }
    }

    #[test]
    fn argsort_is_stable_in_total_cmp_order() {
        for n in [0, 3, 600, 20_000] {
            let v = values(n);
            let mut want: Vec<u32> = (0..n as u32).collect();
            want.sort_by(|&a, &b| v[a as usize].total_cmp(&v[b as usize]).then(a.cmp(&b)));
            assert_eq!(argsort(&v), want, "length {n}");
        }
    }

    /// Values whose top digit (sign and exponent) is one for all, or every digit: the passes
    /// that would not move anything are skipped, and the order is still `total_cmp`'s.
    #[test]
    fn sorts_with_constant_digits_skipped() {
        let narrow: Vec<f32> = (0..5000)
            .map(|i| 1.0 + rng::uniform(3, 0, i) as f32 * 0.99)
            .collect();
        let equal = vec![0.25f32; 3000];
        let low_bits: Vec<f32> = (0..4000u32)
            .map(|i| f32::from_bits(0x3f80_0000 | (i * 7919 % 2048)))
            .collect();
        for v in [narrow, equal, low_bits] {
            let mut a = v.clone();
            sort(&mut a);
            let mut b = v.clone();
            b.sort_unstable_by(f32::total_cmp);
            assert_eq!(a, b);
            let mut want: Vec<u32> = (0..v.len() as u32).collect();
            want.sort_by(|&x, &y| v[x as usize].total_cmp(&v[y as usize]).then(x.cmp(&y)));
            assert_eq!(argsort(&v), want);
        }
    }
}
