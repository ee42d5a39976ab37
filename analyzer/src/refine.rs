//! Refinement of a retrieved pattern (Bourque & Dudek 2004, §3.2.2): Nelder–Mead over the
//! pattern's scale, rotation and structural values, minimising the descriptor distance of the
//! rendered structure map to the photo's.
//!
//! The database is a sparse sample of each family's parameter space (a few hundred points in up
//! to seven dimensions, rotation in 22.5° steps), so its nearest entry is a good start but
//! rarely the optimum; the simplex moves from there. As in the paper, the objective is the
//! retrieval distance itself ([`Db::distance`] between descriptors), evaluated on the
//! descriptor's own 128² image: one pattern image and one descriptor per evaluation, a few ms.
//!
//! Coordinates: `ln scale`, rotation in units of 10°, and each value normalised to its range
//! (so one simplex step means the same in every direction); values are clamped into range.
//!
//! Departures from the paper: the budget is a count of evaluations (deterministic: the same
//! photo gives the same result on every machine), and the caller's `step` callback reports
//! progress after each evaluation and may stop early (a time limit, the user's cancel); the
//! best point so far is returned either way.

use crate::db::{DB_SEED, Db, describe_pattern};
use crate::gabor::Descriptor;
use crate::noise::Tile;
use crate::pattern::Pattern;

/// Evaluations per refined start unless the caller says otherwise.
pub const DEFAULT_EVALUATIONS: usize = 40;

/// A refined pattern.
#[derive(Clone, Debug, PartialEq)]
pub struct Refined {
    /// The best pattern found (scale in descriptor texels).
    pub pattern: Pattern,
    /// Its descriptor distance to the query.
    pub distance: f32,
    /// The start's distance.
    pub start_distance: f32,
    /// Evaluations spent.
    pub evaluations: usize,
    /// Whether `step` stopped it before its budget.
    pub stopped: bool,
}

fn to_point(p: &Pattern) -> Vec<f64> {
    let mut x = vec![(p.scale as f64).ln(), p.rotation_deg as f64 / 10.0];
    for (s, v) in p.kind.specs().iter().zip(p.vector()) {
        x.push(s.search_fraction(v) as f64);
    }
    x
}

fn from_point(kind_of: &Pattern, x: &[f64]) -> Pattern {
    let mut p = kind_of.clone();
    // Scales the descriptor image can see: a few texels to a few times its side.
    p.scale = (x[0].exp() as f32).clamp(1.5, 400.0);
    p.rotation_deg = (x[1] * 10.0).rem_euclid(180.0) as f32;
    let values: Vec<f32> = p
        .kind
        .specs()
        .iter()
        .zip(&x[2..])
        .map(|(s, &u)| s.searched((u as f32).clamp(0.0, 1.0)))
        .collect();
    p.set_vector(&values);
    p
}

/// Refines `start` (scale in descriptor texels) towards `query` (already tone-swapped if the
/// match was), with at most `evaluations` evaluations. `step(done, budget)` runs after each;
/// returning `false` stops the search. `tile` is `Tile::new_2d(DB_SEED)`.
pub fn refine(
    db: &Db,
    query: &Descriptor,
    start: &Pattern,
    evaluations: usize,
    tile: &Tile,
    step: &mut dyn FnMut(usize, usize) -> bool,
) -> Refined {
    let used = std::cell::Cell::new(0usize);
    let mut stopped = false;
    let f = |x: &[f64]| -> f64 {
        used.set(used.get() + 1);
        db.pattern_distance(
            query,
            &describe_pattern(&from_point(start, x), DB_SEED, tile),
        ) as f64
    };
    let x0 = to_point(start);
    let start_distance = f(&x0);
    if !step(used.get(), evaluations) {
        return Refined {
            pattern: start.clone(),
            distance: start_distance as f32,
            start_distance: start_distance as f32,
            evaluations: used.get(),
            stopped: true,
        };
    }
    let n = x0.len();
    // Initial simplex: ±15 % in scale, 8° in rotation, 15 % of each value's range.
    let mut simplex: Vec<(Vec<f64>, f64)> = vec![(x0.clone(), start_distance)];
    for i in 0..n {
        if used.get() >= evaluations {
            break;
        }
        let mut x = x0.clone();
        x[i] += match i {
            0 => 0.15,
            1 => 0.8,
            _ if x0[i] > 0.85 => -0.15,
            _ => 0.15,
        };
        let fx = f(&x);
        simplex.push((x, fx));
        if !step(used.get(), evaluations) {
            stopped = true;
            break;
        }
    }
    // Standard coefficients: reflection 1, expansion 2, contraction ½, shrink ½.
    while !stopped && simplex.len() == n + 1 && used.get() < evaluations {
        simplex.sort_by(|a, b| a.1.total_cmp(&b.1));
        let centroid: Vec<f64> = (0..n)
            .map(|i| simplex[..n].iter().map(|(x, _)| x[i]).sum::<f64>() / n as f64)
            .collect();
        let worst = simplex[n].clone();
        let towards = |t: f64| -> Vec<f64> {
            (0..n)
                .map(|i| centroid[i] + t * (worst.0[i] - centroid[i]))
                .collect()
        };
        let xr = towards(-1.0);
        let fr = f(&xr);
        if fr < simplex[0].1 {
            let xe = towards(-2.0);
            let fe = if used.get() < evaluations {
                f(&xe)
            } else {
                f64::INFINITY
            };
            simplex[n] = if fe < fr { (xe, fe) } else { (xr, fr) };
        } else if fr < simplex[n - 1].1 {
            simplex[n] = (xr, fr);
        } else if used.get() >= evaluations {
            // The budget is spent: no contraction; the reflection replaces the worst point
            // where it is better.
            if fr < worst.1 {
                simplex[n] = (xr, fr);
            }
        } else {
            let (xc, fc) = if fr < worst.1 {
                let xc = towards(-0.5);
                let fc = f(&xc);
                (xc, fc)
            } else {
                let xc = towards(0.5);
                let fc = f(&xc);
                (xc, fc)
            };
            if fc < worst.1.min(fr) {
                simplex[n] = (xc, fc);
            } else {
                // Shrink towards the best point.
                let best = simplex[0].0.clone();
                for v in simplex.iter_mut().skip(1) {
                    if used.get() >= evaluations {
                        break;
                    }
                    let x: Vec<f64> = (0..n).map(|i| best[i] + 0.5 * (v.0[i] - best[i])).collect();
                    let fx = f(&x);
                    *v = (x, fx);
                }
            }
        }
        if !step(used.get(), evaluations) {
            stopped = true;
        }
    }
    let best = simplex
        .iter()
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .expect("the start point");
    Refined {
        pattern: from_point(start, &best.0),
        distance: best.1 as f32,
        start_distance: start_distance as f32,
        evaluations: used.get(),
        stopped,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::pattern::PatternKind;

    /// From a start off in scale, rotation and values, the simplex gets nearer to a brick wall
    /// than the start was.
    #[test]
    fn refinement_improves_on_its_start() {
        let db = Db::shipped();
        let tile = Tile::new_2d(DB_SEED);
        let mut target = Pattern::new(PatternKind::Brick, 14.0);
        target.rotation_deg = 12.0;
        let query = describe_pattern(&target, DB_SEED, &tile);
        let mut start = Pattern::new(PatternKind::Brick, 19.0);
        start.rotation_deg = 0.0;
        let mut calls = 0;
        let r = refine(db, &query, &start, 50, &tile, &mut |done, budget| {
            calls += 1;
            assert!(done <= budget);
            true
        });
        assert!(r.evaluations <= 50 && calls > 0);
        assert!(
            r.distance < 0.5 * r.start_distance,
            "{} → {}",
            r.start_distance,
            r.distance
        );
        // Stopping at once returns the start.
        let s = refine(db, &query, &start, 50, &tile, &mut |_, _| false);
        assert!(s.stopped && s.evaluations == 1 && s.pattern == start);
    }
}
