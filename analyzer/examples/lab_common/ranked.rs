//! A development photo's quadrant as the ranking sees it (`coarse_lab`, `descriptor_parts`).

use proctex::db::{Db, Match};
use proctex::gabor::Descriptor;
use proctex::input::Photo;
use proctex::pattern::PatternKind;
use proctex::two_tone::{TwoTone, network_phase, two_tone};

use super::quadrants;

/// A development photo's quadrant at the ranking's size as the ranking sees it: the reduced
/// patch, its two-tone map, its descriptor and the descriptor's pixels per texel, and each
/// family's best database entries for it (paired by network phase as the ranking pairs).
pub struct RankedQuadrant {
    pub small: Photo,
    pub tt: TwoTone,
    pub query: Descriptor,
    pub per_px: f32,
    starts: Vec<Vec<Match>>,
}

impl RankedQuadrant {
    /// `path`'s quadrant `(qx, qy)`, cut as the development set's patches are (TL, TR, BL, BR).
    pub fn of(path: &str, qx: u32, qy: u32) -> RankedQuadrant {
        let photo = Photo::decode(&std::fs::read(path).unwrap()).unwrap();
        let patch = quadrants(&photo).swap_remove((qy * 2 + qx) as usize);
        let small = patch
            .reduced(proctex::retrieve::RANK_SIZE)
            .unwrap_or(patch.clone());
        let tt = two_tone(&small);
        let (sw, sh) = (small.width as usize, small.height as usize);
        let (query, per_px) = proctex::db::query(&tt.structure, sw, sh);
        let net = network_phase(&tt.structure, sw, sh);
        let starts = Db::shipped().top_per_kind_paired(&query, 8, net);
        RankedQuadrant {
            small,
            tt,
            query,
            per_px,
            starts,
        }
    }

    /// Family `kind`'s best database entry for the quadrant.
    pub fn start(&self, kind: PatternKind) -> &Match {
        self.starts
            .iter()
            .find(|v| !v.is_empty() && v[0].pattern.kind == kind)
            .map(|v| &v[0])
            .expect("the family has database entries")
    }
}
