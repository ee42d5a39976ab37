//! A morph's constant tables for the exported morph shaders (`shaders/morph.wgsl` and
//! `shaders/glsl/morph.glsl`): both ends of every segment, the keys' own params, and the
//! constant-index selectors the shaders read them with.

use super::{Lang, offsets_array, params_value};
use crate::error::{Error, Result};
use crate::morph::quat_from_matrix;
use crate::noise::{TILE_2D, TILE_3D};
use crate::params::{MAX_BANDS, MAX_KNOTS, MAX_TONE_KNOTS, Params};
use crate::pattern::{MAX_STOPS, OCTAVES};
use crate::render::Prepared;

/// A morph's keys as the constants of `shaders/morph.wgsl`: per segment both ends' interpolated
/// quantities (knots resampled to the segment's count, as [`crate::morph::morph`] does), and
/// every key's own params for the keys' t (where `morph_path` returns a key exactly).
pub(super) struct MorphTables {
    /// The first key, whose seed (tile and band offsets) the whole morph renders with.
    pub(super) first: Params,
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
        let noise_tone = |m: &Model| m.tone().filter(|t| t.enabled).cloned();
        match (&a.model, &b.model) {
            (Model::Noise(_), Model::Noise(_)) => {
                let (ta, tb) = (noise_tone(&a.model), noise_tone(&b.model));
                if ta.is_none() && tb.is_none() {
                    SegmentStructure {
                        mode: 0,
                        halves: [MorphStructure::NOISE, MorphStructure::NOISE],
                    }
                } else {
                    SegmentStructure {
                        mode: 1,
                        halves: [MorphStructure::noise_tone([ta, tb]), MorphStructure::NOISE],
                    }
                }
            }
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
                    Model::Noise(_) => MorphStructure::noise_tone([noise_tone(ma), None]),
                };
                let second = match mb {
                    Model::Structured(sb) => MorphStructure::new(
                        None,
                        &sb.pattern,
                        [None, Some(&sb.ramp)],
                        [None, tone(sb)],
                    ),
                    Model::Noise(_) => MorphStructure::noise_tone([None, noise_tone(mb)]),
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

    /// The noise model (kind 0: no pattern, no ramp) with its output tone curve blending
    /// from `t[0]` to `t[1]` (`None`: none).
    fn noise_tone(t: [Option<crate::params::Tone>; 2]) -> MorphStructure {
        let mut out = MorphStructure::NOISE;
        out.set_tones(&t);
        out.info[3] = (t[0].is_none() as u32) << 3;
        out
    }

    /// The tone tables of a blend from `t[0]` to `t[1]` (`None`: none), their knot count in
    /// `info[2]` (0: neither has a curve).
    fn set_tones(&mut self, t: &[Option<crate::params::Tone>; 2]) {
        use crate::morph::tone_grid;
        if t[0].is_none() && t[1].is_none() {
            return;
        }
        let grid = tone_grid(t[0].as_ref(), t[1].as_ref());
        self.info[2] = grid.n as u32;
        for c in 0..3 {
            let [lo, hi] = grid.range[c];
            self.tone_range[0][c] = lo;
            self.tone_range[1][c] = 1.0 / (hi - lo);
            for k in 0..grid.n {
                self.tone[0][k][c] = grid.a[c][k];
                self.tone[1][k][c] = grid.b[c][k];
            }
        }
    }

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
        use crate::morph::{ramp_table, ramp_union, shorter_turn};
        use crate::render::pattern::ramp_rows;
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
        out.set_tones(&t);
        out.info = [p[0].kind.index(), at.len() as u32, out.info[2], flags];
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
    /// The finest band's part after the histogram per channel, unused.
    fine: [f32; 4],
    weights: [[f32; 4]; MAX_BANDS],
    /// Per band: `asin √strength` (the phase `crate::morph::morph_strength` interpolates),
    /// streak angle (degrees), turn to the segment's other end (degrees, linear:
    /// `crate::morph::morph_orientation`), unused.
    orient: [[f32; 4]; MAX_BANDS],
    knots: [[f32; 4]; MAX_KNOTS],
}

impl MorphTables {
    pub(super) fn new(keys: &[Params]) -> Result<MorphTables> {
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
                let orient: Vec<_> = (0..MAX_BANDS)
                    .map(|j| crate::morph::orientation_ends(ma, mb, j))
                    .collect();
                let end = |p: &Params, m: &crate::params::NoiseModel, side: usize| {
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
                        fine: [m.fine[0], m.fine[1], m.fine[2], 0.0],
                        weights: [[0.0; 4]; MAX_BANDS],
                        orient: [[0.0; 4]; MAX_BANDS],
                        knots: [[0.0; 4]; MAX_KNOTS],
                    };
                    for (j, (oa, ob)) in orient.iter().enumerate() {
                        let o = if side == 0 { oa } else { ob };
                        key.orient[j] = [
                            crate::morph::strength_phase(o.strength),
                            o.angle_deg,
                            ob.angle_deg - oa.angle_deg,
                            0.0,
                        ];
                    }
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
                    ends: [end(&w[0], ma, 0), end(&w[1], mb, 1)],
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
    pub(super) fn constants(&self, lang: Lang) -> String {
        let key = |k: &MorphKey| {
            format!(
                "MorphKey(\n    {},\n    {},\n    {},\n    {},\n    {},\n    {},\n    {}\n)",
                lang.vec4(k.mean),
                lang.vec4(k.quat),
                lang.vec4(k.pose),
                lang.vec4(k.fine),
                lang.array(k.weights.iter().copied(), MAX_BANDS),
                lang.array(k.orient.iter().copied(), MAX_BANDS),
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
                MAX_BANDS,
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
                MAX_BANDS,
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
