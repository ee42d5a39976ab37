//! The retrieval database (two-tone paper §5): descriptors of every structured model over its
//! parameter space, built by `proctex build-db`, shipped inside the library
//! (`analyzer/data/patterns.ptxdb`), searched by nearest descriptor.
//!
//! Sampling: per pattern family [`samples`] parameter sets, every structural value
//! uniform in its range and the scale log-uniform in [`SCALES`] texels of the descriptor image,
//! from the project's hash (stream [`rng::stream::DB`]), so the build is deterministic. Rotation
//! is not sampled: [`Descriptor::rotated`] turns an entry by permuting its orientations, and
//! the tone swap is matched by [`Descriptor::swapped`] of the query.
//!
//! Size (the paper's databases were 14 MB–2.9 GB): descriptors are quantised to one byte per
//! entry between the database's per-entry minimum and maximum: 2,560 models per family (5,120 for perlin and cells), 3.5 MB,
//! built in about 115 s on 2 cores. Measured on the synthetic round trip (`tests/retrieval.rs`,
//! 72 cases): with 320 per family (0.36 MB) the refined structure distance alone found the
//! right family 42 times, with 2,560 47 times.

use crate::error::{Error, Result};
use crate::gabor::{
    Descriptor, FREQUENCIES, LEN, ORIENTATIONS, csf_weights, describe, descriptor_image,
};
use crate::noise::Tile;
use crate::pattern::{Pattern, PatternKind};
use crate::render::pattern::structure_image;
use crate::rng;

/// Parameter sets per pattern family.
pub const SAMPLES_PER_KIND: usize = 2560;

/// Parameter sets of `kind`: [`SAMPLES_PER_KIND`], twice that for perlin and cells, whose
/// misses on the synthetic round trip were search failures (the query's own parameters nearer
/// than the refined result, every start far from them in scale: a scale-8 perlin stretched 16×
/// retrieved at scale 50, cells at half their scale) rather than near ties with another family.
/// Measured: 62/72 → 63/72 (a cells and a turbulence case found, a wood-lines case lost to
/// rings), database 2.9 → 3.5 MB.
pub fn samples(kind: PatternKind) -> usize {
    match kind {
        PatternKind::Perlin | PatternKind::Cells => 2 * SAMPLES_PER_KIND,
        _ => SAMPLES_PER_KIND,
    }
}
/// Range of pattern scales sampled, texels of the descriptor image.
pub const SCALES: [f32; 2] = [3.0, 40.0];
/// Seed of the database's patterns (their noise tile and cell hashes).
pub const DB_SEED: u32 = 1;
const MAGIC: &[u8; 8] = b"PTXDB\x00\x00\x01";

/// One model in the database.
#[derive(Clone, Debug, PartialEq)]
pub struct Entry {
    /// The pattern (rotation 0).
    pub pattern: Pattern,
    /// Its descriptor.
    pub descriptor: Descriptor,
}

/// The database.
#[derive(Clone, Debug, PartialEq)]
pub struct Db {
    /// Every entry.
    pub entries: Vec<Entry>,
    /// Distance weight of every descriptor entry: contrast sensitivity over the entry's
    /// variance across the database.
    pub weights: Vec<f32>,
}

/// A retrieved model.
#[derive(Clone, Debug, PartialEq)]
pub struct Match {
    /// Index into [`Db::entries`].
    pub entry: usize,
    /// The pattern, turned to the query's orientation (scale still in descriptor texels).
    pub pattern: Pattern,
    /// The photo's tones pair with the pattern reversed.
    pub swapped: bool,
    /// Weighted descriptor distance.
    pub distance: f32,
}

/// The `i`-th sample of `kind`.
pub fn sample(kind: PatternKind, i: usize) -> Pattern {
    let k = kind.index();
    let u = |j: usize| {
        rng::uniform(
            DB_SEED,
            rng::stream::DB,
            (k << 24) | ((i as u32) << 4) | j as u32,
        ) as f32
    };
    let (lo, hi) = (SCALES[0].ln(), SCALES[1].ln());
    let mut p = Pattern::new(kind, (lo + (hi - lo) * u(15)).exp());
    let values: Vec<f32> = kind
        .specs()
        .iter()
        .enumerate()
        .map(|(j, s)| s.searched(u(j)))
        .collect();
    p.set_vector(&values);
    if kind == PatternKind::Rings {
        // The centre inside the middle 60 % of the descriptor image, not uniform over its
        // range: rings far from their centre are straight lines (the wood-lines family).
        let side = crate::gabor::SIZE as f32;
        for (j, name) in [(12, "centre_x"), (13, "centre_y")] {
            let texel = side * (0.2 + 0.6 * u(j));
            p.set(name, texel / p.scale);
        }
    }
    p
}

/// Finest frequencies of the bank where [`Db::pattern_distance`] forgives a query's excess.
pub const GRAIN_FREQUENCIES: usize = 1;

/// Whether descriptor entry `i` is a mean or spread at one of the [`GRAIN_FREQUENCIES`].
#[inline]
fn grain_entry(i: usize) -> bool {
    i < 2 * ORIENTATIONS * FREQUENCIES && i % FREQUENCIES < GRAIN_FREQUENCIES
}

/// The descriptor of a pattern rendered at one texel per pixel on the descriptor image, with
/// the noise tile of `seed`.
pub fn describe_pattern(p: &Pattern, seed: u32, tile: &Tile) -> Descriptor {
    let n = crate::gabor::SIZE as u32;
    describe(&structure_image(p, seed, tile, n, n))
}

impl Db {
    /// Builds the database (`progress(done, total)` after each entry; rayon on native).
    pub fn build(progress: &(dyn Fn(usize, usize) + Sync)) -> Db {
        let jobs: Vec<(PatternKind, usize)> = PatternKind::ALL
            .into_iter()
            .flat_map(|k| (0..samples(k)).map(move |i| (k, i)))
            .collect();
        let total = jobs.len();
        let done = std::sync::atomic::AtomicUsize::new(0);
        let tile = Tile::new_2d(DB_SEED);
        let one = |&(kind, i): &(PatternKind, usize)| {
            let pattern = sample(kind, i);
            let descriptor = describe_pattern(&pattern, DB_SEED, &tile);
            progress(
                done.fetch_add(1, std::sync::atomic::Ordering::Relaxed) + 1,
                total,
            );
            Entry {
                pattern,
                descriptor,
            }
        };
        #[cfg(not(target_arch = "wasm32"))]
        let entries: Vec<Entry> = {
            use rayon::prelude::*;
            jobs.par_iter().map(one).collect()
        };
        #[cfg(target_arch = "wasm32")]
        let entries: Vec<Entry> = jobs.iter().map(one).collect();
        let mut db = Db {
            entries,
            weights: vec![],
        };
        // Quantise now, so that the built database equals the one read back from its bytes.
        db = Db::from_bytes(&db.to_bytes()).expect("own bytes parse");
        db
    }

    fn compute_weights(entries: &[Entry]) -> Vec<f32> {
        let n = entries.len().max(1) as f64;
        let csf = csf_weights();
        (0..LEN)
            .map(|i| {
                let m = entries
                    .iter()
                    .map(|e| e.descriptor.0[i] as f64)
                    .sum::<f64>()
                    / n;
                let var = entries
                    .iter()
                    .map(|e| (e.descriptor.0[i] as f64 - m).powi(2))
                    .sum::<f64>()
                    / n;
                let block = ORIENTATIONS * FREQUENCIES;
                let w = if i < 2 * block {
                    csf[(i % block) % FREQUENCIES] as f64
                } else {
                    // The distribution entries weigh as much as one orientation's worth.
                    (2 * FREQUENCIES) as f64 / crate::gabor::QUANTILES as f64
                };
                (w / (var + 1e-6)) as f32
            })
            .collect()
    }

    /// The distance of a bare pattern's descriptor to a query (a photo's structure map): as
    /// [`Db::distance`], except that where the query has more response than the pattern at the
    /// finest [`GRAIN_FREQUENCIES`] of the bank (means and spreads), the excess costs nothing;
    /// a pattern with more fine response than the query still pays in full. What retrieval and
    /// refinement minimise. Ours, not the papers': a photo's map carries fine grain (pores,
    /// sand, JPEG) that a clean pattern lacks, and the fitted model's residual noise adds it
    /// back on top of the pattern, so a pattern should not be chosen or bent to draw it.
    /// Measured: the brick sample ranks brick first (planks before, brick a near second), the
    /// reptile skin cells (wood lines before); gravel's best pattern falls from 0.15 to 0.07 of
    /// its self distance (further from structured); synthetic round trip 64 → 65 of 72. With
    /// a database rendered 1.5× supersampled (so that its fine joints do not alias, as a
    /// query's are averaged), the round trip reached 66, but ridged then beat the noise model
    /// on gravel (0.50) and grass (0.30).
    pub fn pattern_distance(&self, query: &Descriptor, pattern: &Descriptor) -> f32 {
        query
            .0
            .iter()
            .zip(&pattern.0)
            .zip(&self.weights)
            .enumerate()
            .map(|(i, ((x, y), w))| {
                if grain_entry(i) && x > y {
                    0.0
                } else {
                    w * (x - y) * (x - y)
                }
            })
            .sum::<f32>()
            .sqrt()
    }

    /// Weighted distance between two descriptors.
    pub fn distance(&self, a: &Descriptor, b: &Descriptor) -> f32 {
        a.0.iter()
            .zip(&b.0)
            .zip(&self.weights)
            .map(|((x, y), w)| w * (x - y) * (x - y))
            .sum::<f32>()
            .sqrt()
    }

    /// For each pattern family, its best entry for the query (every rotation step, both tone
    /// orientations), best first.
    pub fn best_per_kind(&self, query: &Descriptor) -> Vec<Match> {
        let mut out: Vec<Match> = self
            .top_per_kind(query, 1)
            .into_iter()
            .filter_map(|v| v.into_iter().next())
            .collect();
        out.sort_by(|a, b| a.distance.total_cmp(&b.distance));
        out
    }

    /// For each pattern family (in [`PatternKind::ALL`] order), its `k` best entries for the
    /// query, best first; each entry at its best rotation step and tone orientation.
    ///
    /// This loop is the whole retrieval (28,160 entries × 8 rotation steps × 2 tone
    /// orientations), so it does not build the turned descriptors ([`Descriptor::rotated`]) or
    /// take square roots: the orientation entries are indexed as turned, the quantiles (the only
    /// part the tone swap changes, and which rotation leaves alone) are compared once per entry
    /// and orientation, and a rotation step stops summing as soon as its partial squared
    /// distance cannot enter the family's list any more. The distance stored in a [`Match`] is
    /// [`Db::pattern_distance`] of the turned descriptor.
    pub fn top_per_kind(&self, query: &Descriptor, k: usize) -> Vec<Vec<Match>> {
        self.top_per_kind_paired(query, k, None)
    }

    /// [`Db::top_per_kind`] for a query whose bright half is its connected network
    /// (`Some(true)`), its dark half (`Some(false)`) or neither clearly (`None`; see
    /// [`crate::two_tone::network_phase`]): a family with a network of its own
    /// ([`PatternKind::network`]) is then paired network to network, whatever the quantiles
    /// say; the others keep the tone orientation whose quantiles are nearer.
    pub fn top_per_kind_paired(
        &self,
        query: &Descriptor,
        k: usize,
        network: Option<bool>,
    ) -> Vec<Vec<Match>> {
        const BLOCK: usize = ORIENTATIONS * FREQUENCIES;
        let q = &query.0;
        let qs = query.swapped();
        let w = &self.weights;
        let mut top: Vec<Vec<Match>> = vec![Vec::new(); PatternKind::ALL.len()];
        for (i, e) in self.entries.iter().enumerate() {
            let list = &mut top[e.pattern.kind.index() as usize - 1];
            // Squared distance a candidate must stay under (∞ until the list is full).
            let bound = if list.len() < k {
                f32::INFINITY
            } else {
                let d = list[list.len() - 1].distance;
                d * d
            };
            let d = &e.descriptor.0;
            let quant = |qv: &[f32]| -> f32 {
                (2 * BLOCK..LEN)
                    .map(|j| w[j] * (qv[j] - d[j]) * (qv[j] - d[j]))
                    .sum()
            };
            let (q_plain, q_swap) = (quant(q), quant(&qs.0));
            let swapped = match (network, e.pattern.kind.network()) {
                (Some(photo), Some(own)) => photo != own,
                _ => q_swap < q_plain,
            };
            let q_part = if swapped { q_swap } else { q_plain };
            if q_part >= bound {
                continue;
            }
            let (mut best, mut at) = (bound - q_part, None);
            for shift in 0..ORIENTATIONS {
                let mut sum = 0.0f32;
                'sum: for part in 0..2 {
                    for o in 0..ORIENTATIONS {
                        let to = (o + shift) % ORIENTATIONS;
                        let (a, b) = (
                            part * BLOCK + to * FREQUENCIES,
                            part * BLOCK + o * FREQUENCIES,
                        );
                        for f in 0..FREQUENCIES {
                            let x = q[a + f] - d[b + f];
                            if f >= GRAIN_FREQUENCIES || x <= 0.0 {
                                sum += w[a + f] * x * x;
                            }
                        }
                        if sum >= best {
                            break 'sum;
                        }
                    }
                }
                if sum < best {
                    (best, at) = (sum, Some(shift));
                }
            }
            let Some(shift) = at else { continue };
            let turned = e.descriptor.rotated(shift);
            let distance = self.pattern_distance(if swapped { &qs } else { query }, &turned);
            if list.len() < k || distance < list[list.len() - 1].distance {
                let mut pattern = e.pattern.clone();
                pattern.rotation_deg = shift as f32 * 180.0 / ORIENTATIONS as f32;
                let m = Match {
                    entry: i,
                    pattern,
                    swapped,
                    distance,
                };
                let pos = list.partition_point(|x| x.distance <= m.distance);
                list.insert(pos, m);
                list.truncate(k);
            }
        }
        top
    }

    /// The bytes of the database file.
    pub fn to_bytes(&self) -> Vec<u8> {
        let (lo, hi) = self.bounds();
        let mut out = Vec::new();
        out.extend_from_slice(MAGIC);
        out.extend_from_slice(&(self.entries.len() as u32).to_le_bytes());
        out.extend_from_slice(&(LEN as u32).to_le_bytes());
        for v in lo.iter().chain(&hi) {
            out.extend_from_slice(&v.to_le_bytes());
        }
        for e in &self.entries {
            let p = &e.pattern;
            out.push(p.kind.index() as u8);
            out.extend_from_slice(&p.scale.to_le_bytes());
            let values = p.vector();
            out.push(values.len() as u8);
            for v in values {
                out.extend_from_slice(&v.to_le_bytes());
            }
            for i in 0..LEN {
                out.push(level(e.descriptor.0[i], lo[i], hi[i]) as u8);
            }
        }
        out
    }

    /// Each descriptor value's least and greatest over the entries: the 8-bit levels' bounds
    /// ([`level`]) that the file stores.
    fn bounds(&self) -> (Vec<f32>, Vec<f32>) {
        let mut lo = vec![f32::INFINITY; LEN];
        let mut hi = vec![f32::NEG_INFINITY; LEN];
        for e in &self.entries {
            for i in 0..LEN {
                lo[i] = lo[i].min(e.descriptor.0[i]);
                hi[i] = hi[i].max(e.descriptor.0[i]);
            }
        }
        (lo, hi)
    }

    /// Reads a database file.
    pub fn from_bytes(bytes: &[u8]) -> Result<Db> {
        let bad = |what: &str| Error::Decode(format!("pattern database: {what}"));
        let mut at = 0usize;
        let mut take = |n: usize| -> Result<&[u8]> {
            let s = bytes.get(at..at + n).ok_or_else(|| bad("truncated"))?;
            at += n;
            Ok(s)
        };
        if take(8)? != MAGIC {
            return Err(bad("not a proctex pattern database (or another version)"));
        }
        let u32_of = |s: &[u8]| u32::from_le_bytes(s.try_into().unwrap());
        let f32_of = |s: &[u8]| f32::from_le_bytes(s.try_into().unwrap());
        let count = u32_of(take(4)?) as usize;
        if u32_of(take(4)?) as usize != LEN {
            return Err(bad("descriptor length differs from this version's"));
        }
        let mut lo = vec![0.0f32; LEN];
        let mut hi = vec![0.0f32; LEN];
        for v in lo.iter_mut().chain(hi.iter_mut()) {
            *v = f32_of(take(4)?);
        }
        let mut entries = Vec::with_capacity(count);
        for _ in 0..count {
            let kind_index = take(1)?[0] as usize;
            let kind = *PatternKind::ALL
                .get(kind_index.wrapping_sub(1))
                .ok_or_else(|| bad("unknown pattern kind"))?;
            let scale = f32_of(take(4)?);
            let nv = take(1)?[0] as usize;
            let mut values = Vec::with_capacity(nv);
            for _ in 0..nv {
                values.push(f32_of(take(4)?));
            }
            let q = take(LEN)?;
            // Level 255 reads back as `hi` exactly (`lo + (hi − lo)` may round), so that
            // writing a database read from bytes gives the same bounds and the same bytes.
            let descriptor = Descriptor(
                (0..LEN)
                    .map(|i| match q[i] {
                        255 => hi[i],
                        l => lo[i] + (hi[i] - lo[i]) * l as f32 / 255.0,
                    })
                    .collect(),
            );
            let mut pattern = Pattern::new(kind, scale);
            pattern.set_vector(&values);
            entries.push(Entry {
                pattern,
                descriptor,
            });
        }
        let weights = Db::compute_weights(&entries);
        Ok(Db { entries, weights })
    }

    /// The database shipped with this version (built by `proctex build-db`).
    pub fn shipped() -> &'static Db {
        use std::sync::OnceLock;
        static DB: OnceLock<Db> = OnceLock::new();
        DB.get_or_init(|| Db::from_bytes(SHIPPED).expect("the shipped database parses (tested)"))
    }
}

/// The shipped database file.
pub const SHIPPED: &[u8] = include_bytes!("../data/patterns.ptxdb");

/// A descriptor value's 8-bit level between its bounds over the database (before the cast, so
/// that a value outside the bounds shows as a level outside 0..=255).
fn level(v: f32, lo: f32, hi: f32) -> f32 {
    let span = hi - lo;
    if span > 0.0 {
        ((v - lo) / span * 255.0).round()
    } else {
        0.0
    }
}

/// The query descriptor of a structure map of `w × h`, and how many of its texels one
/// descriptor pixel covers.
pub fn query(map: &[f32], w: usize, h: usize) -> (Descriptor, f32) {
    let side = w.min(h);
    (
        describe(&descriptor_image(map, w, h)),
        side as f32 / crate::gabor::SIZE as f32,
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The shipped file is what `proctex build-db` builds from this version's patterns and
    /// descriptor (rebuild it with `proctex build-db -o analyzer/data/patterns.ptxdb`), it
    /// round-trips, and it stays far below the 8 MB budget.
    ///
    /// Building all 28,160 entries takes about two minutes on two cores, so by default every
    /// eighth entry of each family is built again and compared with the shipped one (pattern
    /// bit for bit, descriptor level for level under the shipped file's bounds): any change to
    /// a family's sampling, its rendering or the descriptor changes nearly every entry, hence
    /// the sample's. `PROCTEX_TEST=full` builds the whole database and compares the bytes.
    #[test]
    fn shipped_database_is_fresh_and_small() {
        assert!(SHIPPED.len() < 8_000_000, "{} bytes", SHIPPED.len());
        let shipped = Db::shipped();
        let total: usize = PatternKind::ALL.into_iter().map(samples).sum();
        assert_eq!(shipped.entries.len(), total);
        assert!(
            shipped.to_bytes() == SHIPPED,
            "the shipped bytes round-trip"
        );
        if std::env::var("PROCTEX_TEST").as_deref() != Ok("full") {
            let stale = "analyzer/data/patterns.ptxdb is stale: run `proctex build-db -o analyzer/data/patterns.ptxdb`";
            // The file's own bounds (its entries' extremes read back exactly: it round-trips).
            let (lo, hi) = shipped.bounds();
            let tile = Tile::new_2d(DB_SEED);
            let mut first = 0;
            let mut jobs = Vec::new();
            for kind in PatternKind::ALL {
                jobs.extend((0..samples(kind)).step_by(8).map(|i| (kind, i, first + i)));
                first += samples(kind);
            }
            use rayon::prelude::*;
            jobs.par_iter().for_each(|&(kind, i, at)| {
                let pattern = sample(kind, i);
                let kept = &shipped.entries[at].pattern;
                assert!(
                    (pattern.kind, pattern.scale.to_bits(), pattern.vector())
                        == (kept.kind, kept.scale.to_bits(), kept.vector()),
                    "{stale} ({kind:?} {i})"
                );
                let built = describe_pattern(&pattern, DB_SEED, &tile);
                for (j, (b, s)) in built
                    .0
                    .iter()
                    .zip(&shipped.entries[at].descriptor.0)
                    .enumerate()
                {
                    assert_eq!(
                        level(*b, lo[j], hi[j]),
                        level(*s, lo[j], hi[j]),
                        "{stale} ({kind:?} {i}, descriptor value {j})"
                    );
                }
            });
            return;
        }
        let built = Db::build(&|_, _| {});
        let bytes = built.to_bytes();
        assert!(bytes.len() < 8_000_000, "{} bytes", bytes.len());
        assert!(
            bytes == SHIPPED,
            "analyzer/data/patterns.ptxdb is stale: run `proctex build-db -o analyzer/data/patterns.ptxdb`"
        );
        assert_eq!(Db::from_bytes(&bytes).unwrap(), built);
        let total: usize = PatternKind::ALL.into_iter().map(samples).sum();
        assert_eq!(Db::shipped().entries.len(), total);
    }

    /// The pruned search returns what the exhaustive one does: every entry turned by every
    /// rotation step against both tone orientations, the `k` nearest per family.
    #[test]
    fn pruned_search_equals_exhaustive_search() {
        let db = Db::shipped();
        for (n, kind) in [PatternKind::Brick, PatternKind::Ridged, PatternKind::Rings]
            .into_iter()
            .enumerate()
        {
            let mut p = sample(kind, 7 + 100 * n);
            p.rotation_deg = 30.0 * n as f32;
            let q = describe_pattern(&p, 5, &Tile::new_2d(5));
            let k = 6;
            let got = db.top_per_kind(&q, k);
            let queries = [q.clone(), q.swapped()];
            for (fam, list) in got.iter().enumerate() {
                let mut all: Vec<(f32, usize)> = db
                    .entries
                    .iter()
                    .enumerate()
                    .filter(|(_, e)| e.pattern.kind.index() as usize - 1 == fam)
                    .map(|(i, e)| {
                        let d = (0..ORIENTATIONS)
                            .flat_map(|s| queries.iter().map(move |qq| (s, qq)))
                            .map(|(s, qq)| db.pattern_distance(qq, &e.descriptor.rotated(s)))
                            .fold(f32::INFINITY, f32::min);
                        (d, i)
                    })
                    .collect();
                all.sort_by(|a, b| a.0.total_cmp(&b.0));
                assert_eq!(list.len(), k);
                for (m, (d, i)) in list.iter().zip(&all) {
                    assert_eq!(m.entry, *i, "family {fam}");
                    assert!(
                        (m.distance - d).abs() <= 1e-5 * d.max(1.0),
                        "{} vs {d}",
                        m.distance
                    );
                }
            }
        }
    }

    #[test]
    fn corrupt_database_bytes_give_errors() {
        assert!(Db::from_bytes(b"nope").is_err());
        assert!(Db::from_bytes(&SHIPPED[..SHIPPED.len() / 2]).is_err());
    }
}
