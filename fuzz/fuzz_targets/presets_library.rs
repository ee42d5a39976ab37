//! Presets library text → the app's two readers (whole-file Import, and the preset-by-preset
//! read of the stored library); what Import accepts round-trips through its own JSON.
#![no_main]

// The app's presets module is plain Rust; it is included by path because its crate
// (`proctex-web`) carries egui and wgpu, which a fuzz build does not need.
#[path = "../../web/src/presets.rs"]
#[allow(dead_code)]
mod presets;

use libfuzzer_sys::fuzz_target;

fuzz_target!(|text: &str| {
    let each = presets::read_library(text);
    match presets::parse_library(text) {
        Ok(list) => {
            // Import and the stored read agree on a whole library.
            let (read, bad) = each.expect("what Import accepts, the stored read accepts");
            assert!(bad.is_empty());
            assert_eq!(read, list);
            let again = presets::parse_library(&presets::library_json(&list)).expect("round trip");
            assert_eq!(again.len(), list.len());
        }
        Err(e) => assert!(e.len() < 2000, "unbounded error: {} bytes", e.len()),
    }
});
