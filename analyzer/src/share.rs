//! Share links: a params document in a URL's fragment, `#p=` followed by its JSON in base64url
//! (RFC 4648 §5, no padding). A link opens a texture and nothing else: a presets library or any
//! other document in it is refused, so following a link never writes to the user's presets.
//! Links are bounded ([`MAX_FRAGMENT`]) and decoded here, in Rust, so that the page's parsing
//! of untrusted URLs is the code the fuzz target `share_fragment` exercises.

use crate::error::{Error, Result};
use crate::params::{FORMAT, Params};

/// Most characters of a fragment a link may carry (a params document is 2–10 KB; a morph's
/// keys are not shared by link).
pub const MAX_FRAGMENT: usize = 64 * 1024;

const ALPHABET: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789-_";

/// The fragment (with its `#p=`) that carries `params`.
pub fn fragment(params: &Params) -> String {
    format!("#p={}", base64url(params.to_json().as_bytes()))
}

/// `bytes` in base64url without padding.
fn base64url(bytes: &[u8]) -> String {
    let mut out = String::with_capacity(bytes.len().div_ceil(3) * 4);
    for chunk in bytes.chunks(3) {
        let b = [
            chunk[0],
            *chunk.get(1).unwrap_or(&0),
            *chunk.get(2).unwrap_or(&0),
        ];
        let v = (b[0] as u32) << 16 | (b[1] as u32) << 8 | b[2] as u32;
        for k in 0..=chunk.len() {
            out.push(ALPHABET[(v >> (18 - 6 * k) & 63) as usize] as char);
        }
    }
    out
}

fn link_error(message: impl Into<String>) -> Error {
    Error::Link(message.into())
}

/// The params a fragment (`#p=…`) carries; the error says what is wrong in a user's words.
pub fn params_of_fragment(fragment: &str) -> Result<Params> {
    let body = fragment
        .strip_prefix("#p=")
        .ok_or_else(|| link_error("this link holds no texture (no #p=…)"))?;
    if body.len() > MAX_FRAGMENT {
        return Err(link_error(format!(
            "this link is {} characters long; a texture link has at most {MAX_FRAGMENT}",
            body.len()
        )));
    }
    let mut bytes = Vec::with_capacity(body.len() * 3 / 4);
    let (mut acc, mut bits) = (0u32, 0u32);
    for c in body.bytes() {
        let v = ALPHABET
            .iter()
            .position(|&a| a == c)
            .ok_or_else(|| link_error("this link is damaged (a character outside base64url)"))?;
        acc = acc << 6 | v as u32;
        bits += 6;
        if bits >= 8 {
            bits -= 8;
            bytes.push((acc >> bits & 0xff) as u8);
        }
    }
    if bits >= 6 {
        return Err(link_error(
            "this link is damaged (cut in the middle of a character)",
        ));
    }
    let text = String::from_utf8(bytes)
        .map_err(|_| link_error("this link is damaged (its text is not UTF-8)"))?;
    let doc = crate::json::parse(&text)
        .map_err(|e| link_error(format!("this link is damaged (not JSON: {e})")))?;
    match doc.get("format").and_then(|f| f.as_str()) {
        Some(FORMAT) => Params::from_json(&text)
            .map_err(|e| link_error(format!("this link's texture is not valid: {e}"))),
        _ => Err(link_error(
            "this link does not hold a texture: links open a texture's params only; a presets \
             library is opened with Import… in the presets panel",
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn params() -> Params {
        let path = format!(
            "{}/../www/samples/stk_blackrock_256.png",
            env!("CARGO_MANIFEST_DIR")
        );
        crate::analyze::analyze_bytes(&std::fs::read(path).unwrap(), &Default::default())
            .unwrap()
            .params
    }

    #[test]
    fn a_texture_round_trips_through_its_link() {
        let p = params();
        let f = fragment(&p);
        assert!(f[3..].bytes().all(|c| ALPHABET.contains(&c)), "{f}");
        assert_eq!(params_of_fragment(&f).unwrap(), p);
    }

    #[test]
    fn libraries_junk_and_huge_links_are_refused_in_words() {
        let encode = |text: &str| format!("#p={}", base64url(text.as_bytes()));
        let library = r#"{"format": "proctex-presets/1", "presets": []}"#;
        let e = params_of_fragment(&encode(library))
            .unwrap_err()
            .to_string();
        assert!(e.contains("links open a texture's params only"), "{e}");
        for (bad, want) in [
            ("#q=abc", "no #p="),
            ("#p=ab$c", "outside base64url"),
            ("#p=a", "cut in the middle"),
            ("#p=_w", "not UTF-8"),
            (&encode("not json"), "not JSON"),
            (&format!("#p={}", "A".repeat(MAX_FRAGMENT + 1)), "at most"),
        ] {
            let e = params_of_fragment(bad).unwrap_err().to_string();
            assert!(e.contains(want), "{bad:.40}: {e}");
            assert!(e.len() < 400, "{e}");
        }
    }
}
