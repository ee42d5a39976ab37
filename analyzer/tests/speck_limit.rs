//! The final fit holds its render to the photo's specks (`structure::FinalFit::finish_whole`), and
//! the automatic choice passes over a first family whose render is speckier than the photo at
//! every fit (`retrieve::SPECK_CLEAN_ROWS`).

use proctex::analyze::Options;
use proctex::db::Db;
use proctex::input::Photo;
use proctex::pattern::PatternKind;
use proctex::retrieve::{ModelChoice, Refinement, analyze_with_model};
use proctex::structure::{FinalFit, fit_structured};

/// Quadrant `i` (top-left, top-right, bottom-left, bottom-right) of development photo `name`.
fn dev_quadrant(name: &str, i: usize) -> Photo {
    let path = format!(
        "{}/../../shared/photos/dev/{name}",
        env!("CARGO_MANIFEST_DIR")
    );
    let photo = Photo::decode(&std::fs::read(path).unwrap()).unwrap();
    proctex::evaluate::quadrants(&photo).unwrap()[i].clone()
}

/// The final fit adopts the first of step 6's fits by score whose render keeps within the speck
/// limit: on the development set's metal siding (its bottom-left quadrant, planks as the
/// automatic analysis refines them) the best score's render has 4.6× the photo's specks, and
/// the fit adopted, a worse score, keeps within 1.5×; `fit_structured` is that fit.
#[test]
fn the_final_fit_adopts_the_best_score_within_the_speck_limit() {
    let photo = dev_quadrant("torcs_metalsiding_256.png", 2);
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

/// Where no fit of the ranking's first family keeps within the speck limit, the automatic
/// choice adopts the next row of the top three whose render does and moves it to the front:
/// the development set's cracked earth (top-left quadrant, seed 1) ranks ridged first, whose
/// crest network renders speckier than the photo at every fit of step 6; cells, second, is
/// adopted. The list keeps every row, ridged marked as passed over, and the analysis is cells'
/// whole fit (`fit_structured`), its render within the limit.
#[test]
fn the_automatic_choice_passes_over_a_first_family_whose_render_is_speckier_than_the_photo() {
    let photo = dev_quadrant("megaglest_crackedearth_256.png", 0);
    let (db, opts) = (Db::shipped(), Options::default());
    let (auto, suggestions) =
        analyze_with_model(db, &photo, &opts, ModelChoice::Auto, Refinement::default());
    let names: Vec<&str> = suggestions.iter().map(|s| s.name).collect();
    assert_eq!(&names[..2], ["cells", "ridged"], "{names:?}");
    assert!(!suggestions[0].speckier && suggestions[1].speckier);
    assert!(suggestions[2..].iter().all(|s| !s.speckier));
    // Ridged's whole fit, as a pick of its row fits it: over the limit.
    let (ridged, swapped) = suggestions[1].pattern.clone().unwrap();
    let fit = FinalFit::new(db, &photo, &ridged, &opts, swapped);
    let whole = fit.finish_whole_checked(fit.scored_fits(db));
    assert!(!whole.speck_clean);
    // Cells' whole fit is the analysis, within the limit.
    let (cells, swapped) = suggestions[0].pattern.clone().unwrap();
    assert_eq!(auto, fit_structured(db, &photo, &cells, &opts, swapped));
    let fit = FinalFit::new(db, &photo, &cells, &opts, swapped);
    assert!(fit.within_speck_limit(&auto));
}
