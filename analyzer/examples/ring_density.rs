//! Prints the measured radial power densities of our wavelet-noise bands as the Rust constant
//! `ring_fit::RING_DENSITY` (see `ring_fit::measure_ring_density`), for
//! `analyzer/src/ring_density_table.rs`.
use proctex::ring_fit::{DENSITY_SEEDS, DENSITY_SIZE, measure_ring_density};

fn main() {
    let table = measure_ring_density(DENSITY_SIZE, &DENSITY_SEEDS);
    println!("pub const RING_DENSITY: [[f64; DENSITY_BINS]; DENSITY_BANDS] = [");
    for row in &table {
        let cells: Vec<String> = row.iter().map(|v| format!("{v:.6e}")).collect();
        println!("    [");
        for chunk in cells.chunks(6) {
            println!("        {},", chunk.join(", "));
        }
        println!("    ],");
    }
    println!("];");
}
