//! Image bytes → decode (with a 1 MP limit, so that each input is quick) → the noise model's
//! analysis. Any panic, hang or runaway allocation is a bug; errors are expected.
#![no_main]

use libfuzzer_sys::fuzz_target;
use proctex::analyze::{Options, analyze_photo};
use proctex::input::Photo;

fuzz_target!(|data: &[u8]| {
    // The header reader never panics, whatever the bytes.
    let _ = proctex::image_header::read(data);
    if let Ok(photo) = Photo::decode_limited(data, 1 << 20)
        && photo.check_min_size().is_ok()
    {
        let opts = Options {
            size: 256,
            ..Options::default()
        };
        let analysis = analyze_photo(&photo, &opts).expect("a decoded photo analyses");
        analysis.params.validate().expect("analysed params are valid");
    }
});
