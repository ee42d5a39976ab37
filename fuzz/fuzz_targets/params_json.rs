//! Params JSON text → parse and validate; what parses must serialise, parse back to the same
//! params, render a few pixels on the CPU and export as WGSL and GLSL.
#![no_main]

use libfuzzer_sys::fuzz_target;
use proctex::params::Params;
use proctex::render::{View, render};

fuzz_target!(|text: &str| {
    let Ok(p) = Params::from_json(text) else {
        return;
    };
    let again = Params::from_json(&p.to_json()).expect("serialised params parse");
    assert_eq!(again.to_json(), p.to_json());
    let img = render(&p, 8, 8, &View::default());
    assert!(img.pixels.iter().flatten().all(|v| v.is_finite()));
    for format in ["wgsl", "glsl"] {
        proctex::export::shader(std::slice::from_ref(&p), format).expect("valid params export");
    }
});
