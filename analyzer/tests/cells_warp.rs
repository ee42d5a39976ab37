//! Cells' `warp` bends the lattice by a smooth displacement (two fractal noises, octaves of
//! four cells and finer). Past a point the displacement folds the plane (the displaced
//! lattice's Jacobian determinant ≤ 0 somewhere): a cell's pieces then land in several places
//! and the cells become worm-shaped fragments, no longer stones or scales. The analysis searches
//! warp only up to where it still bends (`ValueSpec::search_max`); the slider keeps the whole
//! range.
use proctex::noise::Tile;
use proctex::params::pattern_shell;
use proctex::pattern::{Pattern, PatternKind, ValueSpec};
use proctex::render::Prepared;
use proctex::render::pattern::cells_warp_field;

/// The displacement's gradient (∂gx/∂x, ∂gx/∂y, ∂gy/∂x, ∂gy/∂y, per unit of warp, in cells)
/// at 40 000 points of the plane, the renderer's own field (every octave unfaded: cells of 64
/// pixels).
fn warp_gradients() -> Vec<[f32; 4]> {
    let tile = Tile::new_2d(1);
    let prep = Prepared::new(&pattern_shell(
        Pattern::new(PatternKind::Cells, 64.0),
        1,
        false,
    ));
    let field = |p: [f32; 2]| cells_warp_field(&prep, &tile, p, 0.0, -6.0, [0.0, 0.0]);
    let h = 0.01f32;
    let mut out = Vec::with_capacity(40_000);
    for i in 0..200 {
        for j in 0..200 {
            let p = [0.37 + i as f32 * 0.31, 0.11 + j as f32 * 0.29];
            let f = field(p);
            let fx = field([p[0] + h, p[1]]);
            let fy = field([p[0], p[1] + h]);
            out.push([
                (fx[0] - f[0]) / h,
                (fy[0] - f[0]) / h,
                (fx[1] - f[1]) / h,
                (fy[1] - f[1]) / h,
            ]);
        }
    }
    out
}

/// The fraction of the plane where `warp` folds the lattice.
fn folded(gradients: &[[f32; 4]], warp: f32) -> f32 {
    let n = gradients
        .iter()
        .filter(|g| (1.0 + warp * g[0]) * (1.0 + warp * g[3]) - warp * g[1] * warp * g[2] <= 0.0)
        .count();
    n as f32 / gradients.len() as f32
}

fn warp_spec() -> ValueSpec {
    *PatternKind::Cells
        .specs()
        .iter()
        .find(|s| s.name == "warp")
        .expect("cells have a warp")
}

#[test]
fn the_searched_warp_bends_the_lattice_without_folding_it() {
    let g = warp_gradients();
    for w in [0.1f32, 0.2, 0.25, 0.3, 0.4, 0.5, 0.7, 1.0] {
        println!(
            "warp {w:.2}: {:.2} % of the plane folded",
            100.0 * folded(&g, w)
        );
    }
    let spec = warp_spec();
    // The searched range ends at the largest warp (in steps of 0.05) that folds less than a
    // thousandth of the plane; the next step folds more.
    assert!(
        folded(&g, spec.search_max) < 1e-3,
        "{}",
        folded(&g, spec.search_max)
    );
    assert!(folded(&g, spec.search_max + 0.05) >= 1e-3);
    // The slider's end folds a good part of it: a look a user may want, not a photo's stones.
    assert!(folded(&g, spec.max) > 0.1, "{}", folded(&g, spec.max));
    assert!(spec.search_max < spec.max && spec.min == 0.0);
}
