//! A URL fragment → the share link's texture, or a bounded error; a texture that opens has a
//! link that opens it again.
#![no_main]

use libfuzzer_sys::fuzz_target;
use proctex::share::{fragment, params_of_fragment};

fuzz_target!(|text: &str| {
    match params_of_fragment(text) {
        Ok(p) => assert_eq!(params_of_fragment(&fragment(&p)).expect("own link opens"), p),
        Err(e) => assert!(e.to_string().len() < 1000),
    }
});
