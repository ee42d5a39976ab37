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

use crate::error::{Error, Result};
use crate::morph::quat_from_matrix;
use crate::noise::{TILE_2D, TILE_3D};
use crate::params::{MAX_BANDS, MAX_KNOTS, MAX_TONE_KNOTS, Params};
use crate::pattern::{MAX_STOPS, OCTAVES};
use crate::render::{Prepared, tile_for};
use crate::rng::stream;

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
    lang.array(
        (0..3)
            .flat_map(|c| (0..MAX_BANDS).map(move |j| (c, j)))
            .map(|(c, j)| {
                let o = p.offsets[c][j];
                [o[0], o[1], o[2], 0.0]
            }),
        3 * MAX_BANDS,
    )
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
        "Params(\n    {},\n    {basis},\n    {},\n    {},\n    {},\n    {weights},\n    {offsets},\n    {knots},\n    {tangents},\n    {},\n    {},\n    {values},\n    {octaves},\n    {ramp},\n    {tone_range},\n    {tone_knots},\n    {tone_tangents}\n)",
        lang.vec4([p.mean[0], p.mean[1], p.mean[2], p.contrast]),
        lang.vec4([p.inv_scale, p.rot[0], p.rot[1], 0.0]),
        lang.uvec4([p.bands, p.knots, p.solid as u32, p.histogram as u32]),
        lang.vec4([p.sigma[0], p.sigma[1], p.sigma[2], 0.0]),
        lang.uvec4(p.pattern),
        lang.vec4(p.pattern_transform),
    )
}

/// The tile-bake constants of a texture (its 2D or 3D tile, from the seed).
fn bake_inputs(params: &Params) -> (u32, u32, u32, f64, f64) {
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
        tile.stats.raw_mean,
        1.0 / tile.stats.raw_variance.sqrt(),
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
/// as the tile-bake passes with `#define PROCTEX_PASS 1|2|3` (plane) or `1|2|3|4` (solid), each
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
    let bake = proctex_shaders::bake_constants(n, seed, stream, mean, inv_sd);
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
    let bake = gl::bake_constants(n, seed, stream, mean, inv_sd);
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

/// A morph's keys as the constants of `shaders/morph.wgsl`: per segment both ends' interpolated
/// quantities (knots resampled to the segment's count, as [`crate::morph::morph`] does), and
/// every key's own params for the keys' t (where `morph_path` returns a key exactly).
struct MorphTables {
    /// The first key, whose seed (tile and band offsets) the whole morph renders with.
    first: Params,
    /// Per segment: its two ends, the blend's counts and its structured models.
    segments: Vec<MorphSegment>,
    /// The params at each key's t: `keys[i]` with the first key's seed, and the end of the path.
    ends: Vec<Prepared>,
    /// The pattern octaves' offsets of the first key's seed.
    pattern_offsets: [[f32; 3]; OCTAVES],
}

/// One segment of a morph (struct `MorphSegment` of `shaders/morph.wgsl`).
struct MorphSegment {
    ends: [MorphKey; 2],
    counts: [u32; 4],
    structure: SegmentStructure,
}

/// The structured models along a segment, as [`crate::morph::morph`] blends them: `mode` 0
/// (two noise models), 1 (one family: `halves[0]` all the way) or 2 (a cross-fade: `halves[0]`
/// for t < ½, `halves[1]` after).
struct SegmentStructure {
    mode: u32,
    halves: [MorphStructure; 2],
}

impl SegmentStructure {
    fn new(a: &Params, b: &Params) -> SegmentStructure {
        use crate::params::Model;
        let tone = |m: &crate::params::StructuredModel| m.tone.clone().filter(|t| t.enabled);
        match (&a.model, &b.model) {
            (Model::Noise(_), Model::Noise(_)) => SegmentStructure {
                mode: 0,
                halves: [MorphStructure::NOISE, MorphStructure::NOISE],
            },
            (Model::Structured(sa), Model::Structured(sb))
                if sa.pattern.kind == sb.pattern.kind =>
            {
                SegmentStructure {
                    mode: 1,
                    halves: [
                        MorphStructure::new(
                            Some([&sa.pattern, &sb.pattern]),
                            &sa.pattern,
                            [Some(&sa.ramp), Some(&sb.ramp)],
                            [tone(sa), tone(sb)],
                        ),
                        MorphStructure::NOISE,
                    ],
                }
            }
            (ma, mb) => {
                let first = match ma {
                    Model::Structured(sa) => MorphStructure::new(
                        None,
                        &sa.pattern,
                        [Some(&sa.ramp), None],
                        [tone(sa), None],
                    ),
                    Model::Noise(_) => MorphStructure::NOISE,
                };
                let second = match mb {
                    Model::Structured(sb) => MorphStructure::new(
                        None,
                        &sb.pattern,
                        [None, Some(&sb.ramp)],
                        [None, tone(sb)],
                    ),
                    Model::Noise(_) => MorphStructure::NOISE,
                };
                SegmentStructure {
                    mode: 2,
                    halves: [first, second],
                }
            }
        }
    }
}

/// A structured model from `u = 0` to `u = 1` (struct `MorphStructure` of `shaders/morph.wgsl`):
/// every table the shader interpolates, computed here as [`crate::morph`] computes them.
struct MorphStructure {
    info: [u32; 4],
    transform: [f32; 4],
    pose: [f32; 4],
    /// values at 0, at 1, their minima and maxima (two vec4 each).
    values: [[[f32; 4]; 2]; 4],
    ramp: [[[f32; 4]; MAX_STOPS]; 2],
    tone_range: [[f32; 4]; 2],
    tone: [[[f32; 4]; MAX_TONE_KNOTS]; 2],
}

impl MorphStructure {
    /// The noise model: nothing to blend.
    const NOISE: MorphStructure = MorphStructure {
        info: [0; 4],
        transform: [0.0; 4],
        pose: [0.0; 4],
        values: [[[0.0; 4]; 2]; 4],
        ramp: [[[0.0; 4]; MAX_STOPS]; 2],
        tone_range: [[0.0; 4]; 2],
        tone: [[[0.0; 4]; MAX_TONE_KNOTS]; 2],
    };

    /// From pattern `moving[0]` to `moving[1]` (the same family; `None` in a cross-fade's half,
    /// whose pattern is `fixed` all the way), ramp `r[0]` to `r[1]` (`None`: the flat ramp at
    /// the blend's mean colour, at the other's stops) and tone curve `t[0]` to `t[1]` (`None`:
    /// none).
    fn new(
        moving: Option<[&crate::pattern::Pattern; 2]>,
        fixed: &crate::pattern::Pattern,
        r: [Option<&Vec<crate::pattern::RampStop>>; 2],
        t: [Option<crate::params::Tone>; 2],
    ) -> MorphStructure {
        use crate::morph::{ramp_table, ramp_union, shorter_turn, tone_grid};
        use crate::pattern::ramp_rows;
        let mut out = MorphStructure::NOISE;
        let p = moving.unwrap_or([fixed, fixed]);
        let flags = moving.is_some() as u32
            | (r[0].is_none() as u32) << 1
            | (r[1].is_none() as u32) << 2
            | (t[0].is_none() as u32) << 3;
        let (ra, rb) = match r {
            [Some(a), Some(b)] => (a, b),
            [Some(a), None] => (a, a),
            [None, Some(b)] => (b, b),
            [None, None] => unreachable!("a structured half has a ramp"),
        };
        let at = ramp_union(ra, rb);
        let (ta, tb) = (ramp_table(ra), ramp_table(rb));
        for (i, &x) in at.iter().enumerate() {
            let (ca, cb) = (ramp_rows(&ta, x), ramp_rows(&tb, x));
            out.ramp[0][i] = [ca[0], ca[1], ca[2], x];
            out.ramp[1][i] = [cb[0], cb[1], cb[2], x];
        }
        out.transform = crate::render::pattern_transform(p[0]);
        out.pose = [
            p[0].scale.ln(),
            p[0].rotation_deg,
            shorter_turn(p[0].rotation_deg, p[1].rotation_deg),
            p[1].scale.ln(),
        ];
        let (va, vb) = (p[0].vector(), p[1].vector());
        for (i, spec) in p[0].kind.specs().iter().enumerate() {
            let (row, col) = (i / 4, i % 4);
            out.values[0][row][col] = va[i];
            out.values[1][row][col] = vb[i];
            out.values[2][row][col] = spec.min;
            out.values[3][row][col] = spec.max;
        }
        let mut tone_knots = 0;
        if t[0].is_some() || t[1].is_some() {
            let grid = tone_grid(t[0].as_ref(), t[1].as_ref());
            tone_knots = grid.n as u32;
            for c in 0..3 {
                let [lo, hi] = grid.range[c];
                out.tone_range[0][c] = lo;
                out.tone_range[1][c] = 1.0 / (hi - lo);
                for k in 0..grid.n {
                    out.tone[0][k][c] = grid.a[c][k];
                    out.tone[1][k][c] = grid.b[c][k];
                }
            }
        }
        out.info = [p[0].kind.index(), at.len() as u32, tone_knots, flags];
        out
    }

    /// The value of `struct MorphStructure` in `lang`.
    fn value(&self, lang: Lang) -> String {
        let arr2 = |a: &[[f32; 4]; 2]| lang.array(a.iter().copied(), 2);
        format!(
            "MorphStructure(\n    {},\n    {},\n    {},\n    {},\n    {},\n    {},\n    {},\n    {},\n    {},\n    {},\n    {},\n    {}\n)",
            lang.uvec4(self.info),
            lang.vec4(self.transform),
            lang.vec4(self.pose),
            arr2(&self.values[0]),
            arr2(&self.values[1]),
            arr2(&self.values[2]),
            arr2(&self.values[3]),
            lang.array(self.ramp[0].iter().copied(), MAX_STOPS),
            lang.array(self.ramp[1].iter().copied(), MAX_STOPS),
            arr2(&self.tone_range),
            lang.array(self.tone[0].iter().copied(), MAX_TONE_KNOTS),
            lang.array(self.tone[1].iter().copied(), MAX_TONE_KNOTS),
        )
    }
}

/// One end of a morph segment (struct `MorphKey` of `shaders/morph.wgsl`).
struct MorphKey {
    mean: [f32; 4],
    quat: [f32; 4],
    pose: [f32; 4],
    weights: [[f32; 4]; MAX_BANDS],
    knots: [[f32; 4]; MAX_KNOTS],
}

impl MorphTables {
    fn new(keys: &[Params]) -> Result<MorphTables> {
        if keys.len() < 2 {
            return Err(Error::Option("a morph needs two or more textures".into()));
        }
        for k in keys {
            k.validate()?;
        }
        if keys.iter().any(|k| k.solid != keys[0].solid) {
            return Err(Error::Option(
                "cannot export a morph between plane and solid textures: make them all plane or \
                 all solid"
                    .into(),
            ));
        }
        let seed = keys[0].seed;
        let with_first_seed = |p: &Params| {
            let mut p = p.clone();
            p.seed = seed;
            p.source = None;
            p
        };
        let mut ends: Vec<Prepared> = keys[..keys.len() - 1]
            .iter()
            .map(|k| Prepared::new(&with_first_seed(k)))
            .collect();
        ends.push(Prepared::new(&crate::morph::morph_path(keys, 1.0)?));
        let segments = keys
            .windows(2)
            .map(|w| {
                let (ma, mb) = (w[0].model.noise_layer(), w[1].model.noise_layer());
                let k = ma.histogram.knots[0].len().max(mb.histogram.knots[0].len()) - 1;
                let turn = crate::morph::shorter_turn(
                    w[0].transform.rotation_deg,
                    w[1].transform.rotation_deg,
                );
                let end = |p: &Params, m: &crate::params::NoiseModel| {
                    let q = quat_from_matrix(p.colour.basis.map(|r| r.map(|v| v as f64)));
                    let knots = crate::morph::effective_knots(m, k);
                    let mut key = MorphKey {
                        mean: [
                            p.colour.mean[0],
                            p.colour.mean[1],
                            p.colour.mean[2],
                            p.colour.contrast,
                        ],
                        quat: q.map(|v| v as f32),
                        pose: [p.transform.scale.ln(), p.transform.rotation_deg, turn, 0.0],
                        weights: [[0.0; 4]; MAX_BANDS],
                        knots: [[0.0; 4]; MAX_KNOTS],
                    };
                    for c in 0..3 {
                        for (j, &wt) in m.weights[c].iter().enumerate().take(MAX_BANDS) {
                            key.weights[j][c] = wt;
                        }
                        for (j, &v) in knots[c].iter().enumerate().take(MAX_KNOTS) {
                            key.knots[j][c] = v;
                        }
                    }
                    key
                };
                let counts = [
                    ma.bands().max(mb.bands()) as u32,
                    (k + 1) as u32,
                    w[0].solid as u32,
                    (ma.histogram.enabled || mb.histogram.enabled) as u32,
                ];
                MorphSegment {
                    ends: [end(&w[0], ma), end(&w[1], mb)],
                    counts,
                    structure: SegmentStructure::new(&w[0], &w[1]),
                }
            })
            .collect();
        let tile_n = if keys[0].solid { TILE_3D } else { TILE_2D } as f32;
        Ok(MorphTables {
            first: with_first_seed(&keys[0]),
            segments,
            ends,
            pattern_offsets: crate::render::pattern_offsets(seed, tile_n),
        })
    }

    /// The generated constants of `shaders/morph.wgsl` (or its GLSL twin) in `lang`.
    fn constants(&self, lang: Lang) -> String {
        let key = |k: &MorphKey| {
            format!(
                "MorphKey(\n    {},\n    {},\n    {},\n    {},\n    {}\n)",
                lang.vec4(k.mean),
                lang.vec4(k.quat),
                lang.vec4(k.pose),
                lang.array(k.weights.iter().copied(), MAX_BANDS),
                lang.array(k.knots.iter().copied(), MAX_KNOTS),
            )
        };
        let segments: Vec<String> = self
            .segments
            .iter()
            .map(|seg| {
                format!(
                    "MorphSegment(\n{},\n{},\n{},\n{},\n{},\n{}\n)",
                    key(&seg.ends[0]),
                    key(&seg.ends[1]),
                    lang.uvec4(seg.counts),
                    lang.uvec4([seg.structure.mode, 0, 0, 0]),
                    seg.structure.halves[0].value(lang),
                    seg.structure.halves[1].value(lang),
                )
            })
            .collect();
        let ends: Vec<String> = self.ends.iter().map(|p| params_value(p, lang)).collect();
        let offsets = offsets_array(&self.ends[0], lang);
        let pattern_offsets = lang.array(
            self.pattern_offsets.iter().map(|o| [o[0], o[1], o[2], 0.0]),
            OCTAVES,
        );
        let seed = self.first.seed;
        let (s, e) = (segments.len(), ends.len());
        match lang {
            Lang::Wgsl => format!(
                "const MORPH_SEGMENT_COUNT: u32 = {s}u;\n\
                 const MORPH_SEED: u32 = {seed}u;\n\
                 const MORPH_PATTERN_OFFSETS: array<vec4<f32>, {OCTAVES}> = {pattern_offsets};\n\
                 const MORPH_OFFSETS: array<vec4<f32>, {}> = {offsets};\n\
                 const MORPH_SEGMENTS: array<MorphSegment, {s}> = array<MorphSegment, {s}>(\n{}\n);\n\
                 const MORPH_ENDS: array<Params, {e}> = array<Params, {e}>(\n{}\n);\n{}",
                3 * MAX_BANDS,
                segments.join(",\n"),
                ends.join(",\n"),
                constant_selectors(lang, s, e),
            ),
            Lang::Glsl => format!(
                "const uint MORPH_SEGMENT_COUNT = {s}u;\n\
                 const uint MORPH_SEED = {seed}u;\n\
                 const vec4 MORPH_PATTERN_OFFSETS[{OCTAVES}] = {pattern_offsets};\n\
                 const vec4 MORPH_OFFSETS[{}] = {offsets};\n\
                 const MorphSegment MORPH_SEGMENTS[{s}] = MorphSegment[{s}](\n{}\n);\n\
                 const Params MORPH_ENDS[{e}] = Params[{e}](\n{}\n);\n{}",
                3 * MAX_BANDS,
                segments.join(",\n"),
                ends.join(",\n"),
                constant_selectors(lang, s, e),
            ),
        }
    }
}

/// `morph_segment(i)` and `morph_end(i)`: segment i and key i of the morph's constant arrays,
/// each read with a constant index in one case of a switch. Indexed at run time, a constant
/// array of structs is copied into every invocation's memory before the read, and drivers
/// compile that slowly: a two-key morph took 58 s to compile on Chromium's software adapter
/// (SwiftShader) read with `MORPH_ENDS[i]`, 12 s with these selectors; lavapipe 1.7 s → 0.8 s.
fn constant_selectors(lang: Lang, segments: usize, ends: usize) -> String {
    let selector = |name: &str, ty: &str, array: &str, n: usize| {
        let mut cases = String::new();
        for i in 0..n - 1 {
            cases += &format!("        case {i}u: {{ return {array}[{i}]; }}\n");
        }
        let last = format!("        default: {{ return {array}[{}]; }}\n", n - 1);
        match lang {
            Lang::Wgsl => {
                format!("fn {name}(i: u32) -> {ty} {{\n    switch i {{\n{cases}{last}    }}\n}}\n")
            }
            Lang::Glsl => {
                format!("{ty} {name}(uint i) {{\n    switch (i) {{\n{cases}{last}    }}\n}}\n")
            }
        }
    };
    format!(
        "{}{}",
        selector("morph_segment", "MorphSegment", "MORPH_SEGMENTS", segments),
        selector("morph_end", "Params", "MORPH_ENDS", ends)
    )
}

/// "W x H" of a bake target.
fn atlas_size(w: u32, h: u32, times: &str) -> String {
    format!("{w} {times} {h}")
}

fn glsl_host_notes_plane(n: u32) -> String {
    format!(
        "\
// Proctex texture, exported by `proctex export --format glsl` (params format proctex/1).
// GLSL ES 3.00 (WebGL2). For desktop GLSL, replace the first line with `#version 330 core`.
// This one text is five programs' shaders: insert one line after `#version` to pick the stage.
//   `#define PROCTEX_VERTEX`  the vertex shader of every program: a full-screen triangle,
//                             drawArrays(TRIANGLES, 0, 3) with no attributes;
//   `#define PROCTEX_PASS 1`  bake pass 1 into an R32F target A of {h} x {n}, no textures;
//   `#define PROCTEX_PASS 2`  bake pass 2 into an R32F target B of {n} x {h}, A bound to the
//                             sampler `proctex_bake_src`;
//   `#define PROCTEX_PASS 3`  bake pass 3 into an R32F target T of {n} x {n}, B bound to
//                             `proctex_bake_src`;
//   nothing                   the texture: T bound to `proctex_tile2`, one world unit (one photo
//                             pixel) per screen pixel, y down from the top of a viewport
//                             `proctex_height` pixels high; or call `proctex(p, pixel_size)`
//                             from your own shader (p in world units).
// Bake once (rendering into R32F needs EXT_color_buffer_float in WebGL2); textures are read
// with texelFetch, so NEAREST filtering and no mipmaps.",
        h = n / 2
    )
}

fn glsl_host_notes_solid(n: u32) -> String {
    format!(
        "\
// Proctex solid (3D) texture, exported by `proctex export --format glsl` (params format
// proctex/1). GLSL ES 3.00 (WebGL2). For desktop GLSL, replace the first line with
// `#version 330 core`. This one text is six programs' shaders: insert one line after `#version`
// to pick the stage.
//   `#define PROCTEX_VERTEX`  the vertex shader of every program: a full-screen triangle,
//                             drawArrays(TRIANGLES, 0, 3) with no attributes;
//   `#define PROCTEX_PASS 1`  bake pass 1 into an R32F target A of {a}, no textures;
//   `#define PROCTEX_PASS 2`  bake pass 2 into an R32F target B of {b}, A bound to the sampler
//                             `proctex_bake_src`;
//   `#define PROCTEX_PASS 3`  bake pass 3 into an R32F target C of {b}, B bound to
//                             `proctex_bake_src`;
//   `#define PROCTEX_PASS 4`  bake pass 4 into an R32F target T of {t}, C bound to
//                             `proctex_bake_src`;
//   nothing                   the texture: T bound to `proctex_tile3`; shows the z = 0 slice at
//                             one world unit (one photo pixel) per screen pixel, y down from the
//                             top of a viewport `proctex_height` pixels high. Or call
//                             `proctex3(p, pixel_size)` (p a 3D point in world units) or
//                             `proctex(p, pixel_size)` (the z = 0 plane) from your own shader.
// The targets are 2D atlases of the {n}^3 noise tile's slices (8 slices per row). Bake once
// (rendering into R32F needs EXT_color_buffer_float in WebGL2); textures are read with
// texelFetch, so NEAREST filtering and no mipmaps.",
        a = atlas_size(4 * n, n * n / 8, "x"),
        b = atlas_size(8 * n, n * n / 16, "x"),
        t = atlas_size(8 * n, n * n / 8, "x"),
    )
}

const GLSL_VERTEX: &str = "\
void main() {
    float x = float((gl_VertexID & 1) * 4 - 1);
    float y = float((gl_VertexID >> 1) * 4 - 1);
    gl_Position = vec4(x, y, 0.0, 1.0);
}";

fn wgsl_host_notes_plane(n: u32) -> String {
    format!(
        "\
// Proctex texture, exported by `proctex export --format wgsl` (params format proctex/1).
// Host, once: make three r32float render targets and draw a full-screen triangle (3 vertices,
// no buffers) into each with `vs_bake` and, in order,
//   fs_bake_down_x into A ({h} × {n}), no bindings;
//   fs_bake_down_y into B ({n} × {h}), A bound at @group(0) @binding(0);
//   fs_bake_tile   into T ({n} × {n}), B bound at @group(0) @binding(0).
// Then draw with `vs_main`/`fs_main` (one world unit = one photo pixel per screen pixel), T at
// @group(0) @binding(1) and @binding(2); or call `proctex(p, pixel_size)` from your own
// fragment shader (p in world units).
// Textures are read with textureLoad (unfilterable float is enough).",
        h = n / 2
    )
}

fn wgsl_host_notes_solid(n: u32) -> String {
    format!(
        "\
// Proctex solid (3D) texture, exported by `proctex export --format wgsl` (params format
// proctex/1). Host, once: make four r32float render targets and draw a full-screen triangle
// (3 vertices, no buffers) into each with `vs_bake` and, in order,
//   fs_bake3_down_x into A ({a}), no bindings;
//   fs_bake3_down_y into B ({b}), A bound at @group(0) @binding(0);
//   fs_bake3_down_z into C ({b}), B bound at @group(0) @binding(0);
//   fs_bake3_tile   into T ({t}), C bound at @group(0) @binding(0).
// (2D atlases of the {n}³ noise tile's slices, 8 slices per row.) Then draw with
// `vs_main`/`fs_main` (the z = 0 slice, one world unit = one photo pixel per screen pixel), T at
// @group(0) @binding(1) and @binding(2); or call `proctex3(p, pixel_size)` (p a 3D point in
// world units) or `proctex(p, pixel_size)` (the z = 0 plane) from your own fragment shader.
// Textures are read with textureLoad (unfilterable float is enough).",
        a = atlas_size(4 * n, n * n / 8, "×"),
        b = atlas_size(8 * n, n * n / 16, "×"),
        t = atlas_size(8 * n, n * n / 8, "×"),
    )
}

const WGSL_MORPH_NOTES: &str = "\
// A morph with t as a uniform: fs_main reads t from a 16-byte uniform buffer at @group(0)
// @binding(3) (t in its first f32: 0 the first texture, 1 the last); your own shader calls
// `proctex(p, pixel_size, t)`, which rebuilds the params of t (a few hundred flops) and shades.";

const GLSL_MORPH_NOTES: &str = "\
// A morph with t as a uniform: set `uniform float proctex_t` (0 the first texture, 1 the last)
// for the display program; your own shader calls `proctex(p, pixel_size, t)`, which rebuilds
// the params of t (a few hundred flops) and shades.";

/// The snippet's public functions and the full-screen entry point, in WGSL.
fn wgsl_entry(solid: bool, morph: bool) -> String {
    let (t_param, t_arg, set, t_uniform) = if morph {
        (
            ", t: f32",
            ", t",
            "    params = morph_params(t);\n",
            ", proctex_t.x",
        )
    } else {
        ("", "", "", "")
    };
    let of_t = if morph { " at morph t" } else { "" };
    let mut out = String::new();
    if morph {
        out += "\n// The morph's t in x (0: the first texture, 1: the last).\n\
                @group(0) @binding(3) var<uniform> proctex_t: vec4<f32>;\n";
    }
    if solid {
        out += &format!(
            "\n// The solid texture{of_t} at world point p (photo pixels) for a pixel footprint of\n\
             // pixel_size units.\n\
             fn proctex3(p: vec3<f32>, pixel_size: f32{t_param}) -> vec3<f32> {{\n{set}\
             \x20   return shade(p, log2(pixel_size * params.transform.x));\n}}\n\n\
             // Its z = 0 plane.\n\
             fn proctex(p: vec2<f32>, pixel_size: f32{t_param}) -> vec3<f32> {{\n\
             \x20   return proctex3(vec3<f32>(p, 0.0), pixel_size{t_arg});\n}}\n"
        );
    } else {
        out += &format!(
            "\n// The texture{of_t} at world point p (photo pixels) for a pixel footprint of\n\
             // pixel_size units.\n\
             fn proctex(p: vec2<f32>, pixel_size: f32{t_param}) -> vec3<f32> {{\n{set}\
             \x20   return shade(vec3<f32>(p, 0.0), log2(pixel_size * params.transform.x));\n}}\n"
        );
    }
    out += &format!(
        "
@vertex
fn vs_main(@builtin(vertex_index) i: u32) -> @builtin(position) vec4<f32> {{
    let x = f32(i32(i & 1u) * 4 - 1);
    let y = f32(i32(i >> 1u) * 4 - 1);
    return vec4<f32>(x, y, 0.0, 1.0);
}}

@fragment
fn fs_main(@builtin(position) frag: vec4<f32>) -> @location(0) vec4<f32> {{
    return vec4<f32>(proctex(frag.xy, 1.0{t_uniform}), 1.0);
}}
"
    );
    out
}

/// The snippet's public functions and the display program's `main`, in GLSL.
fn glsl_entry(solid: bool, morph: bool) -> String {
    let (t_param, t_arg, set, t_uniform) = if morph {
        (
            ", float t",
            ", t",
            "    params = morph_params(t);\n",
            ", proctex_t",
        )
    } else {
        ("", "", "", "")
    };
    let of_t = if morph { " at morph t" } else { "" };
    let mut out = String::new();
    if solid {
        out += &format!(
            "\n// The solid texture{of_t} at world point p (photo pixels) for a pixel footprint of\n\
             // pixel_size units.\n\
             vec3 proctex3(vec3 p, float pixel_size{t_param}) {{\n{set}\
             \x20   return shade(p, log2(pixel_size * params.transform.x));\n}}\n\n\
             // Its z = 0 plane.\n\
             vec3 proctex(vec2 p, float pixel_size{t_param}) {{\n\
             \x20   return proctex3(vec3(p, 0.0), pixel_size{t_arg});\n}}\n"
        );
    } else {
        out += &format!(
            "\n// The texture{of_t} at world point p (photo pixels) for a pixel footprint of\n\
             // pixel_size units.\n\
             vec3 proctex(vec2 p, float pixel_size{t_param}) {{\n{set}\
             \x20   return shade(vec3(p, 0.0), log2(pixel_size * params.transform.x));\n}}\n"
        );
    }
    if morph {
        out +=
            "\n// The morph's t (0: the first texture, 1: the last).\nuniform float proctex_t;\n";
    }
    out += &format!(
        "
// Viewport height in pixels: world y grows downwards from the top of the viewport, as in the
// app and the WGSL export (0 if unset: the texture still shows, shifted).
uniform float proctex_height;
layout(location = 0) out vec4 proctex_out;

void main() {{
    vec2 p = vec2(gl_FragCoord.x, proctex_height - gl_FragCoord.y);
    proctex_out = vec4(proctex(p, 1.0{t_uniform}), 1.0);
}}"
    );
    out
}
