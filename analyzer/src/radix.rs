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
        *out = value(k);
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

/// Buckets of one level of [`order_statistics`] (the keys' range split into this many).
const SELECT_BUCKETS: usize = 1 << 14;

/// A bucket of [`order_statistics`] with more keys than this is split again rather than sorted.
const SELECT_SORTED: usize = 1024;

/// The values that sorting `v` in `f32::total_cmp` order would put at `ranks` (each below
/// `v.len()`, in any order, repeats allowed), without sorting all of `v`: the same bits as
/// `sort` then indexing.
///
/// Why: the colour distance keeps 512 quantiles of each of 13 projections of an image, so it
/// needs about a thousand of their 65,536 order statistics; sorting every projection was an
/// eighth of a native analysis (perf, brick crop, one thread). Here the keys' range is cut into
/// [`SELECT_BUCKETS`] equal spans (a monotone map of the key, so the buckets are in order), one
/// pass counts them, a second gathers only the keys of buckets that hold a wanted rank, and
/// those buckets alone are sorted (split again when large).
pub fn order_statistics(v: &[f32], ranks: &[usize]) -> Vec<f32> {
    let keys: Vec<u32> = v.iter().map(|&x| key(x)).collect();
    select_keys(&keys, ranks).into_iter().map(value).collect()
}

/// The inverse of [`key`]: the sign bit set means the value was not negative.
#[inline]
fn value(k: u32) -> f32 {
    let b = if k & 0x8000_0000 != 0 {
        k ^ 0x8000_0000
    } else {
        !k
    };
    f32::from_bits(b)
}

/// [`order_statistics`] on keys: the keys at `ranks` of their ascending order.
fn select_keys(keys: &[u32], ranks: &[usize]) -> Vec<u32> {
    let n = keys.len();
    assert!(ranks.iter().all(|&r| r < n), "a rank past the values");
    let mut out = vec![0u32; ranks.len()];
    // The ranks' indices in ascending order of rank.
    let mut order: Vec<usize> = (0..ranks.len()).collect();
    order.sort_unstable_by_key(|&i| ranks[i]);
    if n <= SELECT_SORTED {
        select_in_place(&mut keys.to_vec(), ranks, &order, 0, &mut out);
        return out;
    }
    let (lo, hi) = keys
        .iter()
        .fold((u32::MAX, 0u32), |(a, b), &k| (a.min(k), b.max(k)));
    if lo == hi {
        out.fill(lo);
        return out;
    }
    // The smallest shift that puts the range in the buckets.
    let mut shift = 0u32;
    while ((hi - lo) >> shift) as usize >= SELECT_BUCKETS {
        shift += 1;
    }
    let bucket = |k: u32| ((k - lo) >> shift) as usize;
    let mut start = vec![0u32; SELECT_BUCKETS + 1];
    for &k in keys {
        start[bucket(k) + 1] += 1;
    }
    for b in 0..SELECT_BUCKETS {
        start[b + 1] += start[b];
    }
    // Each rank's bucket (`start[b] <= r < start[b + 1]`).
    let of_rank: Vec<usize> = ranks
        .iter()
        .map(|&r| start.partition_point(|&s| s as usize <= r) - 1)
        .collect();
    // Where each wanted bucket's keys go in the gathered array (`u32::MAX`: not wanted).
    let mut place = vec![u32::MAX; SELECT_BUCKETS];
    let mut gathered_len = 0u32;
    for &i in &order {
        let b = of_rank[i];
        if place[b] == u32::MAX {
            place[b] = gathered_len;
            gathered_len += start[b + 1] - start[b];
        }
    }
    let mut gathered = vec![0u32; gathered_len as usize];
    let mut fill = place.clone();
    for &k in keys {
        let b = bucket(k);
        if place[b] != u32::MAX {
            gathered[fill[b] as usize] = k;
            fill[b] += 1;
        }
    }
    // Each wanted bucket (its ranks are consecutive in `order`): selected in place, or split
    // again when large.
    for group in order.chunk_by(|&i, &j| of_rank[i] == of_rank[j]) {
        let b = of_rank[group[0]];
        let (first, len) = (start[b] as usize, (start[b + 1] - start[b]) as usize);
        let slice = &mut gathered[place[b] as usize..place[b] as usize + len];
        if len <= SELECT_SORTED {
            select_in_place(slice, ranks, group, first, &mut out);
        } else {
            let local: Vec<usize> = group.iter().map(|&i| ranks[i] - first).collect();
            for (&i, k) in group.iter().zip(select_keys(slice, &local)) {
                out[i] = k;
            }
        }
    }
    out
}

/// The keys of `slice` (which holds ranks `first..` of the whole) at `ranks[i]` for each `i` of
/// `order` (ascending ranks), into `out[i]`: each selected from what lies right of the last.
fn select_in_place(
    slice: &mut [u32],
    ranks: &[usize],
    order: &[usize],
    first: usize,
    out: &mut [u32],
) {
    // The last rank put in place: everything right of it is not smaller.
    let mut placed: Option<usize> = None;
    for &i in order {
        let r = ranks[i] - first;
        if placed != Some(r) {
            let from = placed.unwrap_or(0);
            slice[from..].select_nth_unstable(r - from);
            placed = Some(r);
        }
        out[i] = slice[r];
    }
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

    /// The order statistics are the sorted values' at those ranks, bit for bit: spread,
    /// narrow, equal, piled-up (most values in one bucket, a few far away: split again) and
    /// special values, every rank and a sparse set in any order.
    #[test]
    fn order_statistics_are_the_sorted_values_at_the_ranks() {
        let piled: Vec<f32> = (0..50_000u32)
            .map(|i| {
                if i % 1000 == 0 {
                    -1e6 + i as f32
                } else {
                    0.5 + rng::uniform(5, 0, i) as f32 * 1e-4
                }
            })
            .collect();
        let narrow: Vec<f32> = (0..20_000)
            .map(|i| 1.0 + rng::uniform(3, 0, i) as f32 * 0.01)
            .collect();
        for v in [
            values(65_536),
            values(700),
            values(3),
            narrow,
            piled,
            vec![0.25f32; 5000],
        ] {
            let mut sorted = v.clone();
            sorted.sort_unstable_by(f32::total_cmp);
            let n = v.len();
            let every: Vec<usize> = (0..n).collect();
            let sparse: Vec<usize> = (0..300).map(|i| (i * 7919 + 13) % n).collect();
            for ranks in [every, sparse, vec![n - 1, 0, n / 2, 0]] {
                let got = order_statistics(&v, &ranks);
                let want: Vec<f32> = ranks.iter().map(|&r| sorted[r]).collect();
                let bits = |x: &[f32]| x.iter().map(|f| f.to_bits()).collect::<Vec<_>>();
                assert_eq!(bits(&got), bits(&want), "length {n}");
            }
        }
        assert!(order_statistics(&[1.0, 2.0], &[]).is_empty());
    }
}
