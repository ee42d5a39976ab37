//! Synthetic round trip of retrieval (the two-tone paper's protocol, Bourque & Dudek Fig. 3):
//! each structured model rendered at random parameters, rotations, scales, tones and seeds
//! (none of them the database's) → automatic model choice → the right family must win.

mod common;

use common::round_trip::{case, family_by_retrieval};
use proctex::analyze::Options;
use proctex::db::Db;
use proctex::pattern::PatternKind;
use proctex::retrieve::{Refinement, rank_with};

/// Cases per family: 432 in all, the rate's standard error 2 points. The first 16 cases of each
/// family (144 in all, the earlier size) were a favourable sample: 121 right (84 %) where all
/// 432 give 77.5 % with the same code (docs/measurements.md, "The synthetic round trip at 432
/// cases").
const CASES: usize = 48;
/// By default every third case of each family is run (144 in all, the rate's standard error
/// 3.5 points; about 5 minutes instead of 15 on two cores), with the same guard;
/// `PROCTEX_TEST=full` runs all 432 (the README's row).
const QUICK_STRIDE: usize = 3;
/// The rate measured on all 432 cases when the ranking last changed: 188 of 432 (43.5 %) since
/// the family classifier has no perlin class, a class of one texture
/// (`family_classifier`: perlin 0 of 48, ridged 26, grid 26, brick 30, cells 39, planks 33, wood
/// lines 34; on 183 textures never tuned on 173 → 175 of 268); 163 (37.7 %) since
/// the noise model's margin is 0.35 (`retrieve::NOISE_MODEL_MARGIN`: ridged 25 of 48, grid 23,
/// brick 24, cells 23, planks 32, wood lines 34; on 183 textures never tuned on 165 → 173 of 268);
/// 164 (38.0 %) since ridged's crests are drawn over the noise's change where the pixel is
/// (`render::pattern::ridged_octaves`: ridged 21 → 25 of 48, cells 23 → 24, planks 31 → 32);
/// 158 (36.6 %) since wood lines and rings are drawn at least a pixel wide and averaged over it
/// (`render::pattern::line_profile`: wood lines 33 → 34 of 48); 157 (36.3 %) since
/// ridged's crests are drawn at least a pixel wide and averaged over it (`render::pattern::crest`:
/// ridged 30 → 21 of 48, most of the others to wood lines; on the development set's photos the
/// speck-clean renders 184 → 198 of 208); 165 (38.2 %) since the
/// classifier's nearest family comes first where a family's own render does not explain the
/// photo's margin as well as where the noise model's does not (`retrieve::RENDER_NULL_MARGIN`;
/// brick 30 → 23 of 48, planks 38 → 31, wood lines 37 → 33: on bare patterns the classifier,
/// trained on photos, puts perlin or wood lines nearest, and a fitted render with its residual
/// grain is no bare pattern; on the development set's photos 65 → 69 of 100, on 183 textures
/// never tuned on 150 → 168 of 268); 185 since the noise model's part of that rule (184 before it, with cells' warp searched while
/// it bends); 183 since the classifier reads the photo's cues and its opinion orders the fitted
/// families
/// (`retrieve::CLASSIFIER_WEIGHT`: perlin 2, grid 24, brick 29, cells 24, wood lines 38 of 48;
/// the development set's structured patches labelled 51 → 56 of 100); 198 before, with the
/// classifier trained on the corpus's three batches (190 with the first two) since the families
/// that the family classifier puts first are fitted and ordered by their renders
/// (`retrieve::RENDER_ORDERED`). The classifier was trained on photos of materials, not on clean
/// procedural patterns: it knows no turbulence or rings (0 of 48 each) and few perlin (5 of 48),
/// and it put a labelled family first on more of the development set's real photos (42 → 48 of
/// 100) and of the shipped samples (the brick wall, the planks). Before it, with the three
/// families nearest by structure: 316 of 432; with the family nearest by retrieval fitted beside
/// the classifier's three, 313 (and 48 of 100 on the development set, but the shipped planks
/// back to ridged: docs/devset.md); with it fitted only where the query is unlike every training
/// texture, 259 (266 with the third batch; not kept: the benchmarks' brick crop lost its family
/// and its speed). The test guards against a regression: the rate plus two
/// standard errors must reach it. (The two-tone paper's 90 % is rejected by these cases.)
const MEASURED_RATE: f32 = 188.0 / 432.0;

#[test]
fn synthetic_round_trip_finds_the_right_family() {
    let db = Db::shipped();
    let opts = Options::default();
    // Every case's suggestions at once: the ranking refines the families in parallel, and the
    // last families of one query would leave a core idle (the results do not depend on the
    // order in which rayon runs the work). Only the best family is fitted: the order is the
    // full ranking's (`fitting_the_best_family_alone_gives_the_full_ranking`), and the winner
    // (the best family or the noise model) has its texture distance.
    let stride = if std::env::var("PROCTEX_TEST").as_deref() == Ok("full") {
        1
    } else {
        QUICK_STRIDE
    };
    let per_family = CASES.div_ceil(stride);
    let cases: Vec<(PatternKind, usize)> = PatternKind::ALL
        .into_iter()
        .flat_map(|kind| (0..CASES).step_by(stride).map(move |c| (kind, c)))
        .collect();
    let mut ranked = {
        use rayon::prelude::*;
        cases
            .par_iter()
            .map(|&(kind, c)| {
                let (img, p) = case(kind, c);
                let ranked = rank_with(db, &img, &opts, Refinement::default(), 1, &|_, _| true);
                (ranked, p)
            })
            .collect::<Vec<_>>()
            .into_iter()
    };
    let mut winners = Vec::new();
    let (mut right, mut right_r, mut total) = (0, 0, 0);
    for kind in PatternKind::ALL {
        let (mut own, mut own_r) = (0, 0);
        let mut got = Vec::new();
        for _ in 0..per_family {
            let (s, p) = ranked.next().expect("one ranking per case");
            let first = s[0].name;
            let by_retrieval = family_by_retrieval(&s);
            winners.push(s[0].distance.expect("the winner is fitted"));
            own += usize::from(first == kind.name());
            own_r += usize::from(by_retrieval == kind.name());
            got.push(format!(
                "{first}/{by_retrieval}({:.0}px,{:.0}°)",
                p.scale, p.rotation_deg
            ));
        }
        println!(
            "{:<11} {own:>2}/{per_family} → {}",
            kind.name(),
            got.join(" ")
        );
        right += own;
        right_r += own_r;
        total += per_family;
    }
    println!("by refined retrieval distance alone (no noise model): {right_r}/{total}");
    winners.sort_by(f32::total_cmp);
    let median = winners[winners.len() / 2];
    let p90 = winners[winners.len() * 9 / 10];
    println!(
        "winner's texture distance to the query: median {median:.3}, 90th percentile {p90:.3}"
    );
    let rate = right as f32 / total as f32;
    let se = (rate * (1.0 - rate) / total as f32).sqrt();
    println!(
        "right family: {right}/{total} = {:.1} % ± {:.1}",
        100.0 * rate,
        100.0 * se
    );
    assert!(
        rate + 2.0 * se >= MEASURED_RATE,
        "right family in {right} of {total} cases ({:.1} % ± {:.1}), below the measured {:.1} %",
        100.0 * rate,
        100.0 * se,
        100.0 * MEASURED_RATE
    );
    // Measured on all 432 cases: median 3.14, 90th percentile 5.78 since the noise model's margin
    // is 0.35; 3.07 and 5.81 since wood lines and rings
    // are averaged over the pixel (3.18 and 5.69 before); 3.18 and 5.83 since `RENDER_NULL_MARGIN`
    // covers the families (3.01 and 5.32 with the noise model's part alone, 5.08 before it: the
    // families that rule puts first are farther than the first by score; 5.03 before the
    // classifier's cues and opinion in the order; 5.15 with the first two batches; 2.55 and 3.67
    // with the family nearest by retrieval fitted beside the classifier's three).
    assert!(median <= 3.5 && p90 <= 6.1, "median {median}, p90 {p90}");
}

/// A photo of thin dark cracks: the noise model matches its histogram and spectrum closely
/// enough to come first by texture distance and margin (it did on all four quadrants before
/// the rule), but the skewness says dark network, so the best family (one of the photo's
/// labelled families) comes first and the noise model after the fitted families: the top three
/// are families. A gravel photo has no dark network and keeps the noise model first.
/// (Development-set photos: the choices that `proctex fidelity --set` records.)
#[test]
fn a_dark_network_ranks_the_best_family_above_the_noise_model() {
    use proctex::cues::dark_skewness;
    use proctex::retrieve::{DARK_NETWORK_SKEWNESS, RENDER_ORDERED};
    let db = Db::shipped();
    let opts = Options::default();
    let cracks = common::dev_quadrant("scorched3d_crackedplaster_256.png");
    assert!(dark_skewness(&cracks) < DARK_NETWORK_SKEWNESS);
    let ranked = rank_with(db, &cracks, &opts, Refinement::default(), 1, &|_, _| true);
    let names: Vec<&str> = ranked.iter().map(|s| s.name).collect();
    // The manifest's labels of this photo: ridged or cells.
    assert!(["ridged", "cells"].contains(&names[0]), "{names:?}");
    // The fitted families (the classifier's first three) come before the noise model, the
    // others after it.
    assert_eq!(names[RENDER_ORDERED], "noise", "{names:?}");

    let gravel = common::dev_quadrant("scorched3d_gravel_256.png");
    assert!(dark_skewness(&gravel) > DARK_NETWORK_SKEWNESS);
    let ranked = rank_with(db, &gravel, &opts, Refinement::default(), 1, &|_, _| true);
    assert_eq!(ranked[0].name, "noise");
}

/// A quadrant of the ashlar wall, which the noise model wins by texture distance, looks like
/// brick to the family classifier far more than the noise model's own render of it does
/// (`retrieve::RENDER_NULL_MARGIN`): the classifier's nearest family comes first, the noise model
/// right after the fitted families, though its score is the best. (On gravel the render explains
/// the photo's margin, and the noise model stays first: the test above.)
#[test]
fn a_family_that_the_noise_models_render_does_not_explain_ranks_first() {
    use proctex::retrieve::{
        RENDER_NULL_MARGIN, RENDER_ORDERED, Suggester, class_margin, classify,
    };
    let db = Db::shipped();
    let opts = Options::default();
    let ashlar = common::dev_quadrant("megaglest_ashlar_256.png");
    let classes = classify(&ashlar);
    let nearest = classes.iter().find_map(|(c, _)| *c).expect("a family");
    let noise = Suggester::new(db, &ashlar, &opts, Refinement::default()).fit_noise(db);
    let unexplained = class_margin(&classes, Some(nearest), None)
        - class_margin(
            noise.render_classes.as_deref().expect("classified"),
            Some(nearest),
            None,
        );
    assert!(unexplained > RENDER_NULL_MARGIN, "{unexplained}");
    let ranked = rank_with(db, &ashlar, &opts, Refinement::default(), 1, &|_, _| true);
    let names: Vec<&str> = ranked.iter().map(|s| s.name).collect();
    assert_eq!(names[0], nearest.name(), "{names:?}");
    assert_eq!(names[RENDER_ORDERED], "noise", "{names:?}");
    let best_family = ranked[..RENDER_ORDERED]
        .iter()
        .map(|s| s.score)
        .fold(f32::INFINITY, f32::min);
    let noise_score = ranked[RENDER_ORDERED].score;
    assert!(noise_score <= best_family, "{noise_score} {best_family}");
}

/// The same null for a family that the scores put first: on a quadrant of interlocking pavers,
/// cells come nearest by texture and structure distance (perlin's blotches did while the
/// classifier had a perlin class), but the photo is nearer to the classifier's nearest family
/// (grid, the photo's label) than to cells by more than the threshold, and than cells' own
/// render is by more again, so grid comes first, and the other fitted families follow by their
/// scores.
#[test]
fn a_family_that_the_first_familys_render_does_not_explain_ranks_first() {
    use proctex::pattern::PatternKind;
    use proctex::retrieve::{RENDER_NULL_MARGIN, RENDER_ORDERED, class_margin, classify};
    let db = Db::shipped();
    let opts = Options::default();
    let pavers = common::dev_quadrant("torcs_pavers_512.png");
    let classes = classify(&pavers);
    let nearest = classes.iter().find_map(|(c, _)| *c).expect("a family");
    assert_eq!(nearest, PatternKind::Grid);
    let ranked = rank_with(db, &pavers, &opts, Refinement::default(), 1, &|_, _| true);
    let names: Vec<&str> = ranked.iter().map(|s| s.name).collect();
    assert_eq!(names[0], "grid", "{names:?}");
    // The family with the best score is another fitted one, whose render does not explain the
    // photo's margin for grid over it.
    let fitted = &ranked[..RENDER_ORDERED];
    let best = fitted
        .iter()
        .min_by(|a, b| a.score.total_cmp(&b.score))
        .expect("fitted families");
    assert_ne!(best.name, "grid", "{names:?}");
    let kind = PatternKind::from_name(best.name);
    let render = best.render_classes.as_deref().expect("fitted");
    let photo = class_margin(&classes, Some(nearest), kind);
    let beyond = photo - class_margin(render, Some(nearest), kind);
    assert!(photo > RENDER_NULL_MARGIN, "{photo}");
    assert!(beyond > RENDER_NULL_MARGIN, "{beyond}");
}

/// A quadrant of a pebble bed, which the noise model wins by texture distance and whose margin
/// its render explains, is nearer in the scattering space to the final render of the
/// classifier's nearest family (cells, the photo's label; the first round of its final fit)
/// than to the noise model's render by
/// more than the threshold (`retrieve::NEARER_RENDER_MARGIN`): cells come first, the noise model
/// right after the fitted families, and the recorded margin is the one measured here from the
/// same fits. On gravel the noise model's render is the nearer one, and it stays first.
#[test]
fn a_family_whose_final_render_is_nearer_than_the_noise_models_ranks_first() {
    use proctex::noise::Tile;
    use proctex::retrieve::{
        ModelChoice, NEARER_RENDER_MARGIN, RENDER_ORDERED, analyze_with_model, classify,
        nearer_render_margin,
    };
    use proctex::structure::{FirstRound, fit_structured};
    let db = Db::shipped();
    let opts = Options::default();
    let pebbles = common::dev_quadrant("openarena_pebbles_256.png");
    let nearest = classify(&pebbles)
        .iter()
        .find_map(|(c, _)| *c)
        .expect("a family");
    let ranked = rank_with(db, &pebbles, &opts, Refinement::default(), 1, &|_, _| true);
    let names: Vec<&str> = ranked.iter().map(|s| s.name).collect();
    assert_eq!(names[0], nearest.name(), "{names:?}");
    assert_eq!(names[0], "cells", "{names:?}");
    assert_eq!(names[RENDER_ORDERED], "noise", "{names:?}");
    let noise = &ranked[RENDER_ORDERED];
    let recorded = noise
        .nearer_render_margin()
        .expect("measured where noise led");
    assert!(recorded > NEARER_RENDER_MARGIN, "{recorded}");
    let (pattern, swapped) = ranked[0].pattern.as_ref().expect("a family");
    let round = FirstRound::new(db, &pebbles, pattern, &opts, *swapped);
    let family = round.amplitude_fit().params;
    let margin = nearer_render_margin(
        &pebbles,
        noise.preview.as_ref().expect("fitted"),
        &family,
        &Tile::new_2d(opts.seed),
    );
    assert_eq!(margin, recorded);
    // Choosing it adopts its final fit, which goes on from the ranking's first round: the same
    // as the whole final fit.
    let (auto, _) = analyze_with_model(
        db,
        &pebbles,
        &opts,
        ModelChoice::Auto,
        Refinement::default(),
    );
    assert_eq!(auto, round.complete(db));
    assert_eq!(auto, fit_structured(db, &pebbles, pattern, &opts, *swapped));
    // The families' own rows record nothing.
    assert!(
        ranked[..RENDER_ORDERED]
            .iter()
            .all(|s| s.nearer_render_margin().is_none())
    );

    let gravel = common::dev_quadrant("scorched3d_gravel_256.png");
    let ranked = rank_with(db, &gravel, &opts, Refinement::default(), 1, &|_, _| true);
    assert_eq!(ranked[0].name, "noise");
    let margin = ranked[0]
        .nearer_render_margin()
        .expect("measured where noise led");
    assert!(margin <= NEARER_RENDER_MARGIN, "{margin}");
}

/// A photo no larger than the ranking's copy is ranked unreduced: the noise model's fit there is
/// the analysis that choosing it runs, and the automatic analysis uses it as it is: the same
/// analysis as the noise model's own, and the ranking's noise row shows its params.
#[test]
fn the_noise_model_chosen_on_a_small_photo_is_its_own_analysis() {
    use proctex::analyze::analyze_prepared;
    use proctex::retrieve::{ModelChoice, RANK_SIZE, analyze_with_model};
    let db = Db::shipped();
    let opts = Options::default();
    let gravel = common::dev_quadrant("scorched3d_gravel_256.png");
    assert!(gravel.width.max(gravel.height) <= RANK_SIZE);
    let (auto, ranked) =
        analyze_with_model(db, &gravel, &opts, ModelChoice::Auto, Refinement::default());
    assert_eq!(ranked[0].name, "noise");
    let own = analyze_prepared(&gravel, &opts);
    assert_eq!(auto, own);
    assert_eq!(ranked[0].preview.as_ref(), Some(&own.params));
}

/// The refinement refines the classifier's first three families, whose fits order the list, and
/// no other (each marked skipped); they are the list's fitted families, the best by score first
/// (or the classifier's nearest family, where the first candidate's render does not explain the
/// photo's margin for it: on the stone bricks' quadrant, the noise model's) and the others by
/// their scores, with the noise model first or right after them.
#[test]
fn the_refinement_refines_the_classifiers_first_three_families() {
    use proctex::cues::dark_skewness;
    use proctex::family_classifier::family_order;
    use proctex::pattern::PatternKind;
    use proctex::retrieve::{
        DARK_NETWORK_SKEWNESS, RENDER_NULL_MARGIN, RENDER_ORDERED, class_margin, classify,
    };
    let db = Db::shipped();
    let opts = Options::default();
    for name in ["megaglest_stonebricks_256.png", "scorched3d_gravel_256.png"] {
        let photo = common::dev_quadrant(name);
        let map = proctex::two_tone::two_tone(&photo).structure;
        let (q, _) = proctex::db::query(&map, photo.width as usize, photo.height as usize);
        let cues = proctex::cues::cues(&photo);
        let mut chosen: Vec<&str> = family_order(&q, &cues)
            .iter()
            .take(RENDER_ORDERED)
            .map(|k| k.name())
            .collect();
        let ranked = rank_with(db, &photo, &opts, Refinement::default(), 1, &|_, _| true);
        for s in ranked.iter().filter(|s| s.pattern.is_some()) {
            let fitted = chosen.contains(&s.name);
            assert_eq!(s.refined_distance.is_some(), fitted, "{name}: {}", s.name);
            assert_eq!(s.skipped, !fitted, "{name}: {}", s.name);
            assert_eq!(s.render_ordered, fitted, "{name}: {}", s.name);
            assert_eq!(s.distance.is_some(), fitted, "{name}: {}", s.name);
        }
        // The first rows are the noise model, first or right after those families, and those
        // families: the best by score first, the others by their scores.
        let head: Vec<&str> = ranked[..=RENDER_ORDERED].iter().map(|s| s.name).collect();
        let noise = head.iter().position(|&n| n == "noise");
        assert!(
            matches!(noise, Some(0 | RENDER_ORDERED)),
            "{name}: {head:?}"
        );
        let families: Vec<&str> = head.iter().copied().filter(|&n| n != "noise").collect();
        let best = ranked[..=RENDER_ORDERED]
            .iter()
            .filter(|s| s.pattern.is_some())
            .min_by(|a, b| a.score.total_cmp(&b.score))
            .expect("fitted families");
        if families[0] != best.name {
            // The render-null rule put the classifier's nearest family first: the first
            // candidate by score (the noise model where its score is no larger, off a dark
            // network; else the best family) does not explain the photo's margin for it. For
            // a family the photo's own margin exceeds the threshold as well.
            let classes = classify(&photo);
            let nearest = classes.iter().find_map(|(c, _)| *c).expect("a family");
            assert_eq!(families[0], nearest.name(), "{name}: {head:?}");
            let noise = ranked
                .iter()
                .find(|s| s.name == "noise")
                .expect("noise row");
            let noise_wins =
                dark_skewness(&photo) >= DARK_NETWORK_SKEWNESS && noise.score <= best.score;
            let (winner, kind) = if noise_wins {
                (noise, None)
            } else {
                (best, PatternKind::from_name(best.name))
            };
            let render = winner.render_classes.as_deref().expect("classified");
            let margin = class_margin(&classes, Some(nearest), kind);
            let beyond = margin - class_margin(render, Some(nearest), kind);
            let statistic = if noise_wins {
                beyond
            } else {
                margin.min(beyond)
            };
            assert!(statistic > RENDER_NULL_MARGIN, "{name}: {margin} {beyond}");
        }
        chosen.retain(|&n| n != families[0]);
        let mut rest: Vec<&proctex::retrieve::Suggestion> = ranked[..=RENDER_ORDERED]
            .iter()
            .filter(|s| chosen.contains(&s.name))
            .collect();
        rest.sort_by(|a, b| a.score.total_cmp(&b.score));
        let rest: Vec<&str> = rest.iter().map(|s| s.name).collect();
        assert_eq!(families[1..], rest[..], "{name}: {head:?}");
    }
}

/// The ranking that fits only the families that decide the order (the browser's worker shows
/// it first) has the full ranking's order and scores, and each other family fitted afterwards
/// equals the full ranking's fit, bit for bit; only the candidates that can come first (the
/// render-ordered ones) have their renders classified.
#[test]
fn fitting_the_families_that_order_the_list_alone_gives_the_full_ranking() {
    use proctex::retrieve::{RENDER_ORDERED, Suggester};
    let db = Db::shipped();
    let opts = Options::default();
    for name in ["megaglest_stonebricks_256.png", "scorched3d_gravel_256.png"] {
        let photo = common::dev_quadrant(name);
        let mut s = Suggester::new(db, &photo, &opts, Refinement::default());
        while s.step(db, &mut |_, _| true) {}
        let full = s.suggestions(db);
        let mut first = s.ranked(db, 1);
        let fitted: Vec<&str> = first
            .iter()
            .filter(|r| r.preview.is_some())
            .map(|r| r.name)
            .collect();
        assert_eq!(fitted.len(), 1 + RENDER_ORDERED, "{name}: {fitted:?}");
        assert!(fitted.contains(&"noise"), "{name}: {fitted:?}");
        for row in &mut first {
            s.fit(db, row);
        }
        assert!(first == full, "{name}");
        for r in &full {
            assert_eq!(
                r.render_classes.is_some(),
                r.render_ordered,
                "{name}: {}",
                r.name
            );
        }
    }
}

/// Every fitted family's preview (its row's thumbnail) has the reduced photo's fine grain: the
/// render's fine deviation reaches the photo's where the fast fit left it smoother
/// (`structure::grain::match_grain_to`). (The noise model's row, which the step leaves alone, is
/// its analysis: `the_noise_model_chosen_on_a_small_photo_is_its_own_analysis`.)
#[test]
fn every_fitted_familys_preview_has_the_photos_grain() {
    use proctex::params::Model;
    use proctex::render::{View, render};
    use proctex::structure::grain::fine_deviation;
    let db = Db::shipped();
    let opts = Options::default();
    let photo = common::dev_quadrant("megaglest_stonebricks_256.png");
    let target = fine_deviation(&photo.pixels, photo.width as usize, photo.height as usize);
    assert!(target > 1.0, "a grainy photo: {target}");
    let ranked = proctex::retrieve::suggest(db, &photo, &opts);
    let mut structured = 0;
    for row in &ranked {
        let p = row.preview.as_ref().expect("every row fitted");
        if !matches!(p.model, Model::Structured(_)) {
            continue;
        }
        structured += 1;
        let img = render(p, photo.width, photo.height, &View::default());
        let d = fine_deviation(&img.pixels, photo.width as usize, photo.height as usize);
        assert!(
            d > 0.85 * target,
            "{}: {d} against the photo's {target}",
            row.name
        );
    }
    assert!(structured >= 6, "{structured}");
}

/// A family's starts refined one by one and stored in any order (natively in parallel, in the
/// browser's worker and its helpers) give the family's refinement bit for bit; a refinement
/// stopped with one start of a family in ranks that family by that start's result.
#[test]
fn a_familys_starts_stored_in_any_order_are_its_refinement() {
    use proctex::retrieve::Suggester;
    let db = Db::shipped();
    let photo = common::dev_quadrant("megaglest_stonebricks_256.png");
    let start = Suggester::new(db, &photo, &Options::default(), Refinement::default());
    let pairs = start.pending_starts();
    let families = start.pending();
    assert_eq!(
        pairs.len(),
        2 * families.len(),
        "two starts a family: {pairs:?}"
    );
    assert!(!families.is_empty());
    let mut stored = start.clone();
    for &(i, k) in pairs.iter().rev() {
        assert!(stored.pending().contains(&i));
        let r = stored.refine_start(db, i, k, &mut |_, _| true);
        stored.set_refined_start(i, k, r);
    }
    assert!(stored.pending().is_empty() && stored.pending_starts().is_empty());
    for &i in &families {
        let whole = start.refine_family(db, i, &mut |_, _| true);
        assert!(whole.1.is_some());
        assert_eq!(stored.refined(i), &whole, "{:?}", start.family(i));
    }
    // Stopped after the second start of the first family: that family is refined by it, the
    // others keep their retrieved patterns.
    let mut stopped = start.clone();
    let (i, k) = pairs[1];
    let r = stopped.refine_start(db, i, k, &mut |_, _| true);
    stopped.set_refined_start(i, k, r.clone());
    assert!(stopped.pending().contains(&i));
    stopped.settle_partial_starts();
    assert_eq!(stopped.refined(i), &r);
    assert_eq!(stopped.pending(), families[1..]);
    assert!(
        families[1..]
            .iter()
            .all(|&j| stopped.refined(j).1.is_none())
    );
}
