//! DXT1/DXT5 DDS textures decoded (0 A.D.'s terrains in the training corpus, `corpus_lab dds`).

/// An RGB565 colour as 8-bit RGB.
fn rgb565(c: u16) -> [f32; 3] {
    let r = ((c >> 11) & 31) as f32 / 31.0;
    let g = ((c >> 5) & 63) as f32 / 63.0;
    let b = (c & 31) as f32 / 31.0;
    [r, g, b]
}

/// The largest mip level of a DXT1 or DXT5 DDS file no wider than `max_side`, as RGB (0–1,
/// sRGB-encoded values), with its side; `None` for other formats.
pub fn decode_dds(b: &[u8], max_side: usize) -> Option<(usize, Vec<[f32; 3]>)> {
    let u32_at = |i: usize| u32::from_le_bytes([b[i], b[i + 1], b[i + 2], b[i + 3]]) as usize;
    let (h, w) = (u32_at(12), u32_at(16));
    let block = match &b[84..88] {
        b"DXT1" => 8,
        b"DXT5" => 16,
        _ => return None,
    };
    if w != h || w < 128 {
        return None;
    }
    let (mut side, mut offset) = (w, 128);
    while side > max_side {
        offset += (side / 4) * (side / 4) * block;
        side /= 2;
    }
    let mut out = vec![[0.0f32; 3]; side * side];
    for by in 0..side / 4 {
        for bx in 0..side / 4 {
            let at = offset + (by * (side / 4) + bx) * block + block - 8;
            let c0 = u16::from_le_bytes([b[at], b[at + 1]]);
            let c1 = u16::from_le_bytes([b[at + 2], b[at + 3]]);
            let (p0, p1) = (rgb565(c0), rgb565(c1));
            let mix = |t: f32| -> [f32; 3] { [0, 1, 2].map(|k| p0[k] * (1.0 - t) + p1[k] * t) };
            // DXT1's three-colour mode (c0 <= c1) has black for its fourth; DXT5 has none.
            let palette = if c0 > c1 || block == 16 {
                [p0, p1, mix(1.0 / 3.0), mix(2.0 / 3.0)]
            } else {
                [p0, p1, mix(0.5), [0.0; 3]]
            };
            let bits = u32::from_le_bytes([b[at + 4], b[at + 5], b[at + 6], b[at + 7]]);
            for i in 0..16 {
                let (x, y) = (bx * 4 + i % 4, by * 4 + i / 4);
                out[y * side + x] = palette[((bits >> (2 * i)) & 3) as usize];
            }
        }
    }
    Some((side, out))
}
