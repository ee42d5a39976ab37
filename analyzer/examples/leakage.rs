//! Prints the measured leakage matrix of our wavelet-noise bands as the Rust constant
//! `spectrum::LEAKAGE_512` (see `spectrum::measure_leakage`), and the raw band variances.
fn main() {
    let l = proctex::spectrum::measure_leakage(512, &proctex::spectrum::LEAKAGE_SEEDS);
    println!("pub const LEAKAGE_512: [[f64; 8]; 8] = [");
    for row in &l {
        let cells: Vec<String> = row.iter().map(|v| format!("{v:.6}")).collect();
        println!("    [{}],", cells.join(", "));
    }
    println!("];");
    let t = proctex::noise::Tile::new_2d(1);
    println!("// raw 2D band variance {:.5}", t.stats[0].raw_variance);
    let t = proctex::noise::Tile::new_3d(1);
    println!("// raw 3D band variance {:.5}", t.stats[0].raw_variance);
}
