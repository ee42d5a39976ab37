//! A development photo's quadrant as the ranking sees it (`coarse_lab`, `descriptor_parts`).

use proctex::input::Photo;
use proctex::pattern::PatternKind;

use super::quadrants;

/// A development photo's quadrant `(qx, qy)` at the ranking's size as the ranking sees it:
/// the reduced patch, its two-tone map, its descriptor and the descriptor's pixels per texel,
/// and `kind`'s best database start for it (paired by network phase as the ranking pairs).
pub struct RankedQuadrant {
    pub small: Photo,
    pub tt: proctex::two_tone::TwoTone,
    pub query: proctex::gabor::Descriptor,
    pub per_px: f32,
    pub start: proctex::db::Match,
}

/// [`RankedQuadrant`] of `path`'s quadrant `(qx, qy)` for family `kind`.
pub fn ranked_quadrant(path: &str, qx: u32, qy: u32, kind: PatternKind) -> RankedQuadrant {
    use proctex::two_tone::{network_phase, two_tone};
    let photo = Photo::decode(&std::fs::read(path).unwrap()).unwrap();
    // TL, TR, BL, BR, as the development set's patches are cut.
    let patch = quadrants(&photo).swap_remove((qy * 2 + qx) as usize);
    let small = patch
        .reduced(proctex::retrieve::RANK_SIZE)
        .unwrap_or(patch.clone());
    let tt = two_tone(&small);
    let (sw, sh) = (small.width as usize, small.height as usize);
    let (query, per_px) = proctex::db::query(&tt.structure, sw, sh);
    let net = network_phase(&tt.structure, sw, sh);
    let start = proctex::db::Db::shipped()
        .top_per_kind_paired(&query, 8, net)
        .into_iter()
        .find(|v| !v.is_empty() && v[0].pattern.kind == kind)
        .expect("the family has database entries")
        .swap_remove(0);
    RankedQuadrant {
        small,
        tt,
        query,
        per_px,
        start,
    }
}
