//! The final fit holds its render to the photo's specks (`structure::FinalFit::finish_whole`).

use proctex::analyze::Options;
use proctex::db::Db;
use proctex::input::{Crop, Photo};
use proctex::pattern::PatternKind;
use proctex::retrieve::{ModelChoice, Refinement, analyze_with_model};
use proctex::structure::{FinalFit, fit_structured};

/// The final fit adopts the first of step 6's fits by score whose render keeps within the speck
/// limit: on the development set's metal siding (its bottom-left quadrant, planks as the
/// automatic analysis refines them) the best score's render has 4.6× the photo's specks, and
/// the fit adopted, a worse score, keeps within 1.5×; `fit_structured` is that fit.
#[test]
fn the_final_fit_adopts_the_best_score_within_the_speck_limit() {
    let path = format!(
        "{}/../../shared/photos/dev/torcs_metalsiding_256.png",
        env!("CARGO_MANIFEST_DIR")
    );
    let p = Photo::decode(&std::fs::read(&path).unwrap()).unwrap();
    let (w, h) = (p.width / 2, p.height / 2);
    let photo = p.crop(Crop { x: 0, y: h, w, h }).unwrap();
    let (db, opts) = (Db::shipped(), Options::default());
    let kind = ModelChoice::Kind(PatternKind::Planks);
    let (_, suggestions) = analyze_with_model(db, &photo, &opts, kind, Refinement::default());
    let planks = suggestions.iter().find(|s| s.name == "planks").unwrap();
    let (pattern, swapped) = planks.pattern.clone().unwrap();
    let fit = FinalFit::new(db, &photo, &pattern, &opts, swapped);
    let scored = fit.scored_fits(db);
    assert!(fit.tries(scored.len()));
    let mut best = fit.finish(scored.clone());
    fit.match_grain(&mut best);
    assert!(!fit.speck_clean(&best));
    let order = fit.order(&scored);
    let adopted = fit.finish_whole(scored.clone());
    assert!(fit.speck_clean(&adopted));
    let kept = order
        .iter()
        .position(|&i| {
            let mut a = fit.finish([scored[i].clone()]);
            fit.match_grain(&mut a);
            a == adopted
        })
        .expect("the adopted fit is one of step 6's");
    assert!(kept > 0, "not the best score");
    assert_eq!(
        adopted,
        fit_structured(db, &photo, &pattern, &opts, swapped)
    );
}
