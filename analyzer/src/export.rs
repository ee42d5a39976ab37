//! Export: the texture as a self-contained WGSL shader that renders the same image as the CPU
//! reference renderer in someone else's engine.
//!
//! The snippet is the app's own shader library (`shaders/`: noise, histogram, texture) with the
//! params baked in as a module-scope value instead of a uniform, plus `shaders/bake.wgsl`,
//! which rebuilds the 128² noise tile from the seed on the GPU (the tile itself, 16384 numbers,
//! would be too big to paste). The host runs three small bake passes once, then draws with
//! `fs_main` (or calls `proctex(p, pixel_size)` from its own shader).
//!
//! The GLSL snippet is the same library in GLSL ES 3.00 (`shaders/glsl/`, twins of the WGSL),
//! one text that compiles as each of the host's five shaders by a `#define` after `#version`.
//!
//! Solid (3D) textures export too: their 64³ tile is baked by four passes into a 2D atlas of its
//! slices (`shaders/bake3.wgsl`, `atlas3.wgsl`), which every host can render into, and `noise3`
//! reads it through `tile3_atlas.wgsl`; `proctex3(p, pixel_size)` evaluates the solid texture.

mod host;
mod morph_tables;

use crate::error::{Error, Result};
use crate::params::{MAX_BANDS, MAX_KNOTS, MAX_TONE_KNOTS, Params};
use crate::pattern::{MAX_STOPS, OCTAVES};
use crate::render::{Prepared, tile_for};
use crate::rng::stream;
use host::{
    GLSL_MORPH_NOTES, GLSL_VERTEX, WGSL_MORPH_NOTES, glsl_entry, glsl_host_notes_plane,
    glsl_host_notes_solid, wgsl_entry, wgsl_host_notes_plane, wgsl_host_notes_solid,
};
use morph_tables::MorphTables;

/// A float as a WGSL literal (tiny values flushed to 0: WGSL rejects subnormal literals).
fn lit(v: f32) -> String {
    let v = if v.abs() < 1e-30 { 0.0 } else { v };
    format!("{v:?}")
}

/// The shading language a value is written in.
#[derive(Clone, Copy)]
enum Lang {
    Wgsl,
    Glsl,
}

impl Lang {
    fn vec4(self, v: [f32; 4]) -> String {
        let ty = match self {
            Lang::Wgsl => "vec4<f32>",
            Lang::Glsl => "vec4",
        };
        format!(
            "{ty}({}, {}, {}, {})",
            lit(v[0]),
            lit(v[1]),
            lit(v[2]),
            lit(v[3])
        )
    }

    fn array(self, rows: impl Iterator<Item = [f32; 4]>, n: usize) -> String {
        let items: Vec<String> = rows.map(|r| format!("        {}", self.vec4(r))).collect();
        let ty = match self {
            Lang::Wgsl => format!("array<vec4<f32>, {n}>"),
            Lang::Glsl => format!("vec4[{n}]"),
        };
        format!("{ty}(\n{}\n    )", items.join(",\n"))
    }

    fn uvec4(self, v: [u32; 4]) -> String {
        let ty = match self {
            Lang::Wgsl => "vec4<u32>",
            Lang::Glsl => "uvec4",
        };
        format!("{ty}({}u, {}u, {}u, {}u)", v[0], v[1], v[2], v[3])
    }
}

/// The band offsets as the `offsets` array of `Params`.
fn offsets_array(p: &Prepared, lang: Lang) -> String {
    lang.array(p.offsets.iter().map(|o| [o[0], o[1], o[2], 0.0]), MAX_BANDS)
}

/// The line of `shaders/glsl/morph.glsl` that the generated constants replace (GLSL needs them
/// after the structs and before the functions).
const GLSL_MORPH_CONSTANTS: &str = "// (generated constants)";

/// The params as a `Params` value (same layout as the app's uniform block) in `lang`.
fn params_value(p: &Prepared, lang: Lang) -> String {
    let basis = lang.array(p.basis.iter().map(|r| [r[0], r[1], r[2], 0.0]), 3);
    let weights = lang.array(
        (0..MAX_BANDS).map(|j| [p.weights[0][j], p.weights[1][j], p.weights[2][j], 0.0]),
        MAX_BANDS,
    );
    let offsets = offsets_array(p, lang);
    let orient = lang.array(p.orient.iter().map(|m| [m[0], m[1], m[2], 0.0]), MAX_BANDS);
    let knots = lang.array(
        (0..MAX_KNOTS).map(|k| {
            [
                p.knot_values[0][k],
                p.knot_values[1][k],
                p.knot_values[2][k],
                0.0,
            ]
        }),
        MAX_KNOTS,
    );
    let tangents = lang.array(
        (0..MAX_KNOTS).map(|k| [p.tangents[0][k], p.tangents[1][k], p.tangents[2][k], 0.0]),
        MAX_KNOTS,
    );
    let w = p.pattern_values;
    let values = lang.array(
        [[w[0], w[1], w[2], w[3]], [w[4], w[5], w[6], w[7]]].into_iter(),
        2,
    );
    let octaves = lang.array(
        p.pattern_offsets.iter().map(|o| [o[0], o[1], o[2], 0.0]),
        OCTAVES,
    );
    let ramp = lang.array(p.ramp.iter().copied(), MAX_STOPS);
    let tone_range = lang.array(p.tone_range.iter().map(|r| [r[0], r[1], r[2], 0.0]), 2);
    let tone_array = |a: &[[f32; MAX_TONE_KNOTS]; 3]| {
        lang.array(
            (0..MAX_TONE_KNOTS).map(|k| [a[0][k], a[1][k], a[2][k], 0.0]),
            MAX_TONE_KNOTS,
        )
    };
    let (tone_knots, tone_tangents) = (tone_array(&p.tone_knots), tone_array(&p.tone_tangents));
    // WGSL allows a trailing comma in a constructor; GLSL does not.
    format!(
        "Params(\n    {},\n    {basis},\n    {},\n    {},\n    {},\n    {},\n    {weights},\n    {offsets},\n    {orient},\n    {knots},\n    {tangents},\n    {},\n    {},\n    {values},\n    {octaves},\n    {ramp},\n    {tone_range},\n    {tone_knots},\n    {tone_tangents}\n)",
        lang.vec4([p.mean[0], p.mean[1], p.mean[2], p.contrast]),
        lang.vec4([p.inv_scale, p.rot[0], p.rot[1], 0.0]),
        lang.uvec4([p.bands, p.knots, p.solid as u32, p.histogram as u32]),
        lang.vec4([p.sigma[0], p.sigma[1], p.sigma[2], 0.0]),
        lang.vec4([p.fine[0], p.fine[1], p.fine[2], 0.0]),
        lang.uvec4(p.pattern),
        lang.vec4(p.pattern_transform),
    )
}

/// The tile-bake constants of a texture (its 2D or 3D tile, from the seed).
fn bake_inputs(params: &Params) -> (u32, u32, u32, [f64; 3], [f64; 3]) {
    let tile = tile_for(params);
    let stream = if params.solid {
        stream::TILE_3D
    } else {
        stream::TILE_2D
    };
    (
        tile.n as u32,
        params.seed,
        stream,
        tile.stats.map(|s| s.raw_mean),
        tile.stats.map(|s| 1.0 / s.raw_variance.sqrt()),
    )
}

/// What a snippet renders: one texture, or a morph through two or more with t as a uniform.
enum Subject<'a> {
    Texture(&'a Params),
    Morph(Box<MorphTables>),
}

impl Subject<'_> {
    /// The texture whose tile the snippet bakes (a morph renders with its first key's).
    fn tile_params(&self) -> &Params {
        match self {
            Subject::Texture(p) => p,
            Subject::Morph(m) => &m.first,
        }
    }

    fn is_morph(&self) -> bool {
        matches!(self, Subject::Morph(_))
    }
}

/// The complete WGSL shader of a texture: `proctex(p, pixel_size)` (and `proctex3` for solid
/// textures), the tile-bake passes and a minimal full-screen entry point (`vs_main`/`fs_main`,
/// one world unit per pixel; the z = 0 slice of a solid texture).
pub fn wgsl(params: &Params) -> Result<String> {
    params.validate()?;
    Ok(wgsl_of(&Subject::Texture(params)))
}

/// The complete GLSL ES 3.00 shader of a texture: one text that compiles as the display
/// fragment shader as-is, as the full-screen vertex shader with `#define PROCTEX_VERTEX`, and
/// as the tile-bake passes with `#define PROCTEX_PASS 1|2|3|4|5` (plane) or `1|2|3|4` (solid), each
/// define inserted after the `#version` line.
pub fn glsl(params: &Params) -> Result<String> {
    params.validate()?;
    Ok(glsl_of(&Subject::Texture(params)))
}

/// The complete WGSL shader of the morph through `keys` (as [`crate::morph::morph_path`]) with
/// t as a uniform: as [`wgsl`], and `proctex(p, pixel_size, t)` rebuilds the params of `t` from
/// every key's constants (`shaders/morph.wgsl`).
pub fn morph_wgsl(keys: &[Params]) -> Result<String> {
    Ok(wgsl_of(&Subject::Morph(Box::new(MorphTables::new(keys)?))))
}

/// The complete GLSL ES 3.00 shader of the morph through `keys` with t as the uniform
/// `proctex_t` (stages as [`glsl`]).
pub fn morph_glsl(keys: &[Params]) -> Result<String> {
    Ok(glsl_of(&Subject::Morph(Box::new(MorphTables::new(keys)?))))
}

/// The complete shader in `format` ("wgsl" or "glsl") of one texture (`keys` of one), or of the
/// morph through two or more with t as a uniform: what `proctex export` and the app's Copy
/// buttons write.
pub fn shader(keys: &[Params], format: &str) -> Result<String> {
    match (format, keys) {
        ("wgsl", [p]) => wgsl(p),
        ("glsl", [p]) => glsl(p),
        ("wgsl", _) => morph_wgsl(keys),
        ("glsl", _) => morph_glsl(keys),
        (f, _) => Err(Error::Option(format!(
            "unknown shader language `{f}` (wgsl or glsl)"
        ))),
    }
}

fn wgsl_of(subject: &Subject) -> String {
    let tp = subject.tile_params();
    let (n, seed, stream, mean, inv_sd) = bake_inputs(tp);
    let mut bake = proctex_shaders::bake_constants(n, seed, stream, mean, inv_sd);
    if !tp.solid {
        bake += &proctex_shaders::bake2_constants(crate::noise::spectral::tile2_profile());
    }
    let (header, morph) = match subject {
        Subject::Texture(p) => (
            proctex_shaders::params_private(Some(&params_value(&Prepared::new(p), Lang::Wgsl))),
            String::new(),
        ),
        Subject::Morph(m) => (
            proctex_shaders::params_private(None),
            format!("{}\n{}", m.constants(Lang::Wgsl), proctex_shaders::MORPH),
        ),
    };
    let (notes, passes) = if tp.solid {
        (wgsl_host_notes_solid(n), proctex_shaders::BAKE3)
    } else {
        (wgsl_host_notes_plane(n), proctex_shaders::BAKE2)
    };
    let notes = if subject.is_morph() {
        format!("{notes}\n{WGSL_MORPH_NOTES}")
    } else {
        notes
    };
    let entry = wgsl_entry(tp.solid, subject.is_morph());
    [
        &[
            notes.as_str(),
            &bake,
            &header,
            &morph,
            proctex_shaders::ATLAS3,
            proctex_shaders::TILE3_ATLAS,
        ][..],
        &proctex_shaders::SHADING,
        &[proctex_shaders::BAKE, passes, &entry],
    ]
    .concat()
    .join("\n")
}

fn glsl_of(subject: &Subject) -> String {
    use proctex_shaders::glsl as gl;
    let tp = subject.tile_params();
    let (n, seed, stream, mean, inv_sd) = bake_inputs(tp);
    let mut bake = gl::bake_constants(n, seed, stream, mean, inv_sd);
    if !tp.solid {
        bake += &gl::bake2_constants(crate::noise::spectral::tile2_profile());
    }
    let value = match subject {
        Subject::Texture(p) => format!(
            "const Params params = {};",
            params_value(&Prepared::new(p), Lang::Glsl)
        ),
        Subject::Morph(m) => format!(
            "{}\n// The params of t, set by proctex() before it shades.\nParams params;",
            gl::MORPH.replace(GLSL_MORPH_CONSTANTS, &m.constants(Lang::Glsl))
        ),
    };
    let (notes, solid, bakepasses, tile3) = if tp.solid {
        (
            glsl_host_notes_solid(n),
            "#define PROCTEX_SOLID\n",
            format!("{}\n{}\n{}", gl::ATLAS3, gl::BAKE, gl::BAKE3),
            format!("{}\n{}", gl::ATLAS3, gl::TILE3_ATLAS),
        )
    } else {
        (
            glsl_host_notes_plane(n),
            "",
            format!("{}\n{}", gl::BAKE, gl::BAKE2),
            String::new(),
        )
    };
    let notes = if subject.is_morph() {
        format!("{notes}\n{GLSL_MORPH_NOTES}")
    } else {
        notes
    };
    format!(
        "#version 300 es\n{notes}\n\
         precision highp float;\nprecision highp int;\nprecision highp sampler2D;\n{solid}\
         #if defined(PROCTEX_VERTEX)\n{GLSL_VERTEX}\n\
         #elif defined(PROCTEX_PASS)\n{bake}\n{hash}\n{bakepasses}\n\
         #else\n{params}\n{value}\n{tile3}\n{noise}\n{histogram}\n{hash}\n{pattern}\n{texture}\n{entry}\n\
         #endif\n",
        params = gl::PARAMS,
        noise = gl::NOISE,
        histogram = gl::HISTOGRAM,
        hash = gl::HASH,
        pattern = gl::PATTERN,
        texture = gl::TEXTURE,
        entry = glsl_entry(tp.solid, subject.is_morph()),
    )
}
