//! The development set: real photos, each labelled with its category (structured or
//! stochastic) and the pattern families a good match may use (`manifest.tsv`), and the
//! yardstick that measures on them what a user sees: which model the automatic choice picks for
//! each source patch of the fidelity protocol ([`crate::evaluate::fidelity`]), whether it is a
//! labelled family, and how close the texture comes to the photo next to the noise model's.
//!
//! The yardstick only measures. Any constant chosen by looking at its numbers must be chosen by
//! cross-validation: [`fold_of`] splits the photos into folds by a hash of their file names, so
//! that the folds do not depend on the manifest's order or on which photos were added later.

use crate::error::{Error, Result};
use crate::evaluate::{Fidelity, SynthesisRun};
use crate::pattern::PatternKind;

/// What a photo shows: a structured material (joints, stones, planks) or a stochastic one.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Category {
    Structured,
    Stochastic,
}

/// One photo of the set, as its manifest line says.
#[derive(Clone, Debug, serde::Serialize)]
pub struct Entry {
    /// File name, relative to the manifest's folder.
    pub file: String,
    pub category: Category,
    /// What the photo shows, in words.
    pub material: String,
    /// The families a good match may use ("noise" for the noise model); `None` where the
    /// manifest has no `families` column (the shipped samples' manifest).
    pub families: Option<Vec<String>>,
}

/// Reads a manifest: tab-separated, a header line naming the columns (`file`, `category` and
/// `material` are required, `families` optional, others ignored), one photo per line.
pub fn parse_manifest(text: &str) -> Result<Vec<Entry>> {
    let mut lines = text.lines().filter(|l| !l.trim().is_empty());
    let header: Vec<&str> = lines
        .next()
        .ok_or_else(|| Error::Option("the manifest is empty".into()))?
        .split('\t')
        .map(str::trim)
        .collect();
    let column = |name: &str| header.iter().position(|h| *h == name);
    let need = |name: &str| {
        column(name).ok_or_else(|| {
            Error::Option(format!(
                "the manifest's header has no `{name}` column (it has: {})",
                header.join(", ")
            ))
        })
    };
    let (file, category, material) = (need("file")?, need("category")?, need("material")?);
    let families = column("families");
    let mut out = Vec::new();
    for (i, line) in lines.enumerate() {
        let fields: Vec<&str> = line.split('\t').map(str::trim).collect();
        let at = |c: usize| {
            fields.get(c).copied().ok_or_else(|| {
                Error::Option(format!(
                    "manifest line {}: {} fields, the header has {}",
                    i + 2,
                    fields.len(),
                    header.len()
                ))
            })
        };
        let category = match at(category)? {
            "structured" => Category::Structured,
            "stochastic" => Category::Stochastic,
            other => {
                return Err(Error::Option(format!(
                    "manifest line {}: category `{other}` (structured or stochastic)",
                    i + 2
                )));
            }
        };
        let families = match families {
            Some(c) => {
                let names: Vec<String> = at(c)?.split_whitespace().map(String::from).collect();
                for n in &names {
                    if n != "noise" && PatternKind::from_name(n).is_none() {
                        return Err(Error::Option(format!(
                            "manifest line {}: unknown family `{n}`",
                            i + 2
                        )));
                    }
                }
                Some(names)
            }
            None => None,
        };
        out.push(Entry {
            file: at(file)?.to_string(),
            category,
            material: at(material)?.to_string(),
            families,
        });
    }
    Ok(out)
}

/// The fold (0..`folds`) of a photo: FNV-1a of its file name, so that a photo's fold does not
/// change when others are added or the manifest is reordered.
pub fn fold_of(file: &str, folds: usize) -> usize {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for b in file.bytes() {
        h = (h ^ b as u64).wrapping_mul(0x0100_0000_01b3);
    }
    (h % folds.max(1) as u64) as usize
}

/// Names of the fidelity protocol's source patches, in [`Fidelity::per_patch`] order.
pub const PATCHES: [&str; 4] = ["top-left", "bottom-left", "top-right", "bottom-right"];

/// The automatic choice on one source patch (with the first seed).
#[derive(Clone, Debug, serde::Serialize)]
pub struct PatchChoice {
    /// [`PATCHES`] entry.
    pub patch: &'static str,
    /// The model chosen ("noise" or a family).
    pub chosen: String,
    /// The first three of the ranking.
    pub top3: Vec<String>,
    /// Wall time of the patch's automatic analysis, milliseconds.
    pub analysis_ms: f64,
    /// The whole ranking's numbers, nearest first: what choosing the ranking's constants
    /// again needs without analysing again (the ranking is a function of these).
    pub ranking: Vec<Candidate>,
    /// Speck fractions ([`crate::specks::speck_fraction`]) of the source patch and of the
    /// synthesis of the chosen model; the patch's pixel count (for [`speck_ratio`]).
    pub photo_specks: f64,
    pub render_specks: f64,
    pub pixels: usize,
    /// The source patch's structure cues ([`crate::cues::cues`], in the order of
    /// [`crate::cues::CUE_NAMES`]).
    pub photo_cues: [f32; crate::cues::CUES],
    /// The numbers of the noise model's document as the ranking fitted it on this patch
    /// ([`crate::noise_tone::numbers`], against [`crate::noise_tone::PARAMETER_BUDGET`]).
    pub noise_numbers: usize,
    /// The family classifier's classes for the source patch, nearest first (families' names
    /// and `noise`; [`crate::retrieve::classify`]).
    pub classifier: Vec<String>,
    /// The squared distances of those classes, in the same order
    /// ([`crate::family_classifier::class_distances`]): the first says how far the patch lies
    /// from every texture the classifier was trained on (`corpus_lab table` prints the corpus's
    /// own held-out spread), the others how much nearer one class is than another.
    pub classifier_distances: Vec<f64>,
    /// The classifier's margin for the patch's nearest family over its noise class
    /// ([`crate::retrieve::class_margin`]) on the noise model's render as the ranking rendered
    /// it: with `classifier_distances`, the candidates' own and the ranking's scores, what
    /// choosing [`crate::retrieve::RENDER_NULL_MARGIN`] again needs
    /// (`tools/devset_null_gate_cv.py`).
    pub noise_render_margin: f64,
    /// Where the ranking's other rules put the noise model first: how much nearer the patch is
    /// to the first round of its nearest family's final fit than to the noise model's render in
    /// the scattering space (the ranking's
    /// [`crate::retrieve::Suggestion::nearer_render_margin`]); negative infinity
    /// elsewhere (JSON `null`). What choosing [`crate::retrieve::NEARER_RENDER_MARGIN`] again
    /// needs (`tools/devset_nearer_render_cv.py`).
    pub nearer_render_margin: f64,
    /// Where `nearer_render_margin` is recorded, the patch's two scattering distances whose
    /// difference it is: to the noise model's render and to the family's
    /// ([`crate::retrieve::Suggestion::nearer_render_distances`]).
    pub nearer_render_distances: Option<(f64, f64)>,
}

/// [`crate::noise_tone::numbers`] of the noise model in a ranking (0 if it has none).
fn noise_numbers(ranking: &[crate::retrieve::Suggestion]) -> usize {
    ranking
        .iter()
        .find_map(|c| match c.preview.as_ref().map(|p| &p.model) {
            Some(crate::params::Model::Noise(m)) => Some(crate::noise_tone::numbers(m)),
            _ => None,
        })
        .unwrap_or(0)
}

pub use crate::specks::{SPECK_LIMIT, speck_ratio};

/// One candidate of a patch's ranking (a [`crate::retrieve::Suggestion`]'s numbers).
#[derive(Clone, Debug, serde::Serialize)]
pub struct Candidate {
    pub name: String,
    /// Texture distance of the fitted candidate to the patch.
    pub distance: f32,
    /// The ranking key.
    pub score: f32,
    /// Structure distance by retrieval (0 for the noise model) and after refinement.
    pub retrieval: f32,
    pub refined: Option<f32>,
    /// Speck fraction of the candidate as fitted for the ranking, rendered at the patch's size
    /// with the patch's seed.
    pub specks: f64,
    /// Structure cues of that render ([`crate::cues::cues`]).
    pub cues: [f32; crate::cues::CUES],
    /// The family classifier's squared distances for the candidate's render as the ranking
    /// rendered it, by class name (`noise` for the noise class; [`crate::retrieve::classify`]);
    /// empty for a family after the render-ordered ones, which the ranking does not classify.
    pub classifier_distances: std::collections::BTreeMap<String, f64>,
}

/// One photo measured: the choices, and the fidelity of the automatic choice and of the noise
/// model alone (the same seeds).
#[derive(Clone, Debug, serde::Serialize)]
pub struct PhotoResult {
    pub entry: Entry,
    pub choices: Vec<PatchChoice>,
    pub auto: Fidelity,
    pub noise: Fidelity,
}

/// The mean of a fidelity's three ratios (spectrum, colour, structure): one number per model
/// and photo, 1 meaning as close as another patch of the same photo.
pub fn overall(f: &Fidelity) -> f64 {
    (f.spectrum_ratio + f.colour_ratio + f.structure_ratio) / 3.0
}

/// [`overall`] of one source patch's syntheses (their mean distances over the photo's).
fn patch_overall(f: &Fidelity, patch: usize) -> f64 {
    let d = f.per_patch[patch];
    let h = f.halves;
    (d.spectrum_db / h.spectrum_db.max(1e-9)
        + d.colour / h.colour.max(1e-9)
        + d.structure / h.structure.max(1e-9))
        / 3.0
}

impl PhotoResult {
    /// Measures one photo: `auto_run` runs the fidelity protocol with the automatic choice,
    /// reporting each synthesis; `noise_run` with the noise model alone.
    pub fn measure(
        entry: Entry,
        auto_run: impl FnOnce(&mut dyn FnMut(SynthesisRun)) -> Result<Fidelity>,
        noise_run: impl FnOnce() -> Result<Fidelity>,
    ) -> Result<PhotoResult> {
        let mut choices: Vec<Option<PatchChoice>> = vec![None; PATCHES.len()];
        let auto = auto_run(&mut |run: SynthesisRun| {
            if choices[run.patch].is_none() {
                use crate::evaluate::render_params_at_photo_size;
                use crate::specks::speck_fraction;
                let names: Vec<String> = run.ranking.iter().map(|s| s.name.to_string()).collect();
                let classes = crate::retrieve::classify(run.source);
                let nearest = classes.iter().find_map(|(c, _)| *c);
                // The classes of a candidate's render as the ranking rendered and classified it
                // (none for a family after the render-ordered ones: `retrieve::Fit`).
                let render_classes =
                    |c: &crate::retrieve::Suggestion| c.render_classes.clone().unwrap_or_default();
                let noise_render_margin = run
                    .ranking
                    .iter()
                    .find(|c| c.name == "noise")
                    .map_or(f64::NEG_INFINITY, |c| {
                        crate::retrieve::class_margin(&render_classes(c), nearest, None)
                    });
                let nearer_render_margin = run
                    .ranking
                    .iter()
                    .find_map(|c| c.nearer_render_margin())
                    .unwrap_or(f64::NEG_INFINITY);
                let nearer_render_distances =
                    run.ranking.iter().find_map(|c| c.nearer_render_distances);
                choices[run.patch] = Some(PatchChoice {
                    patch: PATCHES[run.patch],
                    chosen: names.first().cloned().unwrap_or_else(|| "noise".into()),
                    top3: names.into_iter().take(3).collect(),
                    analysis_ms: run.analysis_ms,
                    ranking: run
                        .ranking
                        .iter()
                        .map(|c| {
                            // The automatic analysis ranks with every candidate fitted.
                            let fitted = "every candidate of a full ranking is fitted";
                            let preview = c.preview.as_ref().expect(fitted);
                            let render = render_params_at_photo_size(preview, run.source);
                            Candidate {
                                name: c.name.to_string(),
                                distance: c.distance.expect(fitted),
                                score: c.score,
                                retrieval: c.retrieval_distance,
                                refined: c.refined_distance,
                                specks: speck_fraction(&render),
                                cues: crate::cues::cues(&render),
                                classifier_distances: render_classes(c)
                                    .into_iter()
                                    .map(|(k, d)| (k.map_or("noise", |k| k.name()).into(), d))
                                    .collect(),
                            }
                        })
                        .collect(),
                    photo_specks: speck_fraction(run.source),
                    photo_cues: crate::cues::cues(run.source),
                    noise_numbers: noise_numbers(run.ranking),
                    classifier: classes
                        .iter()
                        .map(|(c, _)| c.map_or("noise", |k| k.name()).to_string())
                        .collect(),
                    classifier_distances: classes.iter().map(|c| c.1).collect(),
                    noise_render_margin,
                    nearer_render_margin,
                    nearer_render_distances,
                    render_specks: speck_fraction(run.synthesis),
                    pixels: run.source.pixels.len(),
                });
            }
        })?;
        let noise = noise_run()?;
        Ok(PhotoResult {
            entry,
            choices: choices.into_iter().flatten().collect(),
            auto,
            noise,
        })
    }

    /// Whether the patch's choice is one of the labelled families (`None`: no labels).
    pub fn labelled(&self, c: &PatchChoice) -> Option<bool> {
        self.entry.families.as_ref().map(|f| f.contains(&c.chosen))
    }

    /// Whether a labelled family is among the patch's first three.
    pub fn top3_labelled(&self, c: &PatchChoice) -> Option<bool> {
        self.entry
            .families
            .as_ref()
            .map(|f| c.top3.iter().any(|t| f.contains(t)))
    }

    /// A stochastic patch is served well when it keeps the noise model, or gets a family whose
    /// texture is no farther from the photo than the noise model's.
    pub fn stochastic_ok(&self, i: usize) -> bool {
        self.choices[i].chosen == "noise"
            || patch_overall(&self.auto, i) <= patch_overall(&self.noise, i)
    }
}

/// A rate over patches with its standard error over photos (the patches of one photo are not
/// independent: the photos are the samples).
#[derive(Clone, Copy, Debug, Default, serde::Serialize)]
pub struct Rate {
    pub hits: usize,
    pub total: usize,
    /// Standard error of the rate: the spread of the per-photo rates over √photos.
    pub standard_error: f64,
}

impl Rate {
    fn of(per_photo: &[(usize, usize)]) -> Rate {
        let hits = per_photo.iter().map(|p| p.0).sum();
        let total = per_photo.iter().map(|p| p.1).sum();
        let rates: Vec<f64> = per_photo
            .iter()
            .filter(|p| p.1 > 0)
            .map(|p| p.0 as f64 / p.1 as f64)
            .collect();
        Rate {
            hits,
            total,
            standard_error: mean_and_error(&rates).1,
        }
    }

    pub fn fraction(&self) -> f64 {
        self.hits as f64 / self.total.max(1) as f64
    }
}

/// The median of sorted values (0 for none).
fn median(sorted: &[f64]) -> f64 {
    match sorted.len() {
        0 => 0.0,
        n if n % 2 == 1 => sorted[n / 2],
        n => 0.5 * (sorted[n / 2 - 1] + sorted[n / 2]),
    }
}

/// Mean and standard error (sample standard deviation over √n; 0 below two samples).
pub fn mean_and_error(v: &[f64]) -> (f64, f64) {
    let n = v.len() as f64;
    if v.is_empty() {
        return (0.0, 0.0);
    }
    let mean = v.iter().sum::<f64>() / n;
    if v.len() < 2 {
        return (mean, 0.0);
    }
    let var = v.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1.0);
    (mean, (var / n).sqrt())
}

/// Fidelity of one category's photos: mean [`overall`] ratios and their difference.
#[derive(Clone, Copy, Debug, Default, serde::Serialize)]
pub struct FidelitySummary {
    /// Photos whose fidelity is defined ([`defined`]), the ones summarised.
    pub photos: usize,
    /// Photos left out: their paired quadrants are the same pixels ([`defined`]).
    pub undefined: usize,
    /// Mean overall ratio of the automatic choice, and its standard error over photos.
    pub auto: (f64, f64),
    /// The same for the noise model alone.
    pub noise: (f64, f64),
    /// Mean of the per-photo differences auto − noise (negative: auto nearer) and its error.
    pub difference: (f64, f64),
    /// Median of the per-photo differences: the mean is dominated by tiled photos whose
    /// paired quadrants are near copies (a small `d(A, B)` makes every ratio large).
    pub median_difference: f64,
    /// Mean of ln(auto / noise) per photo and its error: the same comparison independent of
    /// each photo's own scale (−0.1: auto about 10 % nearer).
    pub log_ratio: (f64, f64),
}

/// Whether a photo's fidelity is defined: the patches of each pair differ. Some tiles repeat
/// with half the photo's period, so that the top and bottom quadrants are the same pixels and
/// every ratio divides by zero (the wood grain of the development set).
pub fn defined(f: &Fidelity) -> bool {
    f.halves.spectrum_db > 1e-6 && f.halves.colour > 1e-9 && f.halves.structure > 1e-6
}

/// The whole set's numbers.
#[derive(Clone, Debug, Default, serde::Serialize)]
pub struct Summary {
    /// Structured patches whose choice is a labelled family.
    pub structured_labelled: Rate,
    /// Structured patches with a labelled family among the first three.
    pub structured_top3: Rate,
    /// Stochastic patches served well ([`PhotoResult::stochastic_ok`]).
    pub stochastic_ok: Rate,
    pub structured_fidelity: FidelitySummary,
    pub stochastic_fidelity: FidelitySummary,
    /// Median analysis time of a patch, per patch side (pixels), milliseconds.
    pub median_ms: Vec<(u32, f64)>,
    /// Label set ("brick/grid", "noise") → chosen model → patches.
    pub confusion: Vec<(String, Vec<(String, usize)>)>,
    /// Patches whose chosen model's synthesis keeps within [`SPECK_LIMIT`] of the photo's
    /// specks.
    pub specks_clean: Rate,
    /// Per model (noise and each family, every patch's fitted candidate): renders, renders past
    /// [`SPECK_LIMIT`], the median and the largest [`speck_ratio`].
    pub specks_by_model: Vec<SpeckRow>,
    /// The noise model's numbers per patch ([`PatchChoice::noise_numbers`]): the least, the
    /// median and the most over the set's patches.
    pub noise_numbers: [usize; 3],
}

/// One model's speck numbers over the set ([`Summary::specks_by_model`]).
#[derive(Clone, Debug, Default, serde::Serialize)]
pub struct SpeckRow {
    pub model: String,
    pub renders: usize,
    pub over_limit: usize,
    pub median_ratio: f64,
    pub max_ratio: f64,
}

impl Summary {
    /// `sides[i]`: the patch side of `results[i]` (for the times).
    pub fn of(results: &[PhotoResult], sides: &[u32]) -> Summary {
        let mut s = Summary::default();
        let count = |r: &PhotoResult, f: &dyn Fn(&PatchChoice) -> Option<bool>| {
            let v: Vec<bool> = r.choices.iter().filter_map(f).collect();
            (v.iter().filter(|&&x| x).count(), v.len())
        };
        let structured: Vec<&PhotoResult> = results
            .iter()
            .filter(|r| r.entry.category == Category::Structured)
            .collect();
        let stochastic: Vec<&PhotoResult> = results
            .iter()
            .filter(|r| r.entry.category == Category::Stochastic)
            .collect();
        s.structured_labelled = Rate::of(
            &structured
                .iter()
                .map(|r| count(r, &|c| r.labelled(c)))
                .collect::<Vec<_>>(),
        );
        s.structured_top3 = Rate::of(
            &structured
                .iter()
                .map(|r| count(r, &|c| r.top3_labelled(c)))
                .collect::<Vec<_>>(),
        );
        s.stochastic_ok = Rate::of(
            &stochastic
                .iter()
                .map(|r| {
                    let ok = (0..r.choices.len()).filter(|&i| r.stochastic_ok(i)).count();
                    (ok, r.choices.len())
                })
                .collect::<Vec<_>>(),
        );
        let fid = |set: &[&PhotoResult]| {
            let kept: Vec<&&PhotoResult> = set.iter().filter(|r| defined(&r.noise)).collect();
            let a: Vec<f64> = kept.iter().map(|r| overall(&r.auto)).collect();
            let n: Vec<f64> = kept.iter().map(|r| overall(&r.noise)).collect();
            let mut d: Vec<f64> = a.iter().zip(&n).map(|(x, y)| x - y).collect();
            let logs: Vec<f64> = a.iter().zip(&n).map(|(x, y)| (x / y).ln()).collect();
            let difference = mean_and_error(&d);
            d.sort_by(f64::total_cmp);
            FidelitySummary {
                photos: kept.len(),
                undefined: set.len() - kept.len(),
                auto: mean_and_error(&a),
                noise: mean_and_error(&n),
                difference,
                median_difference: median(&d),
                log_ratio: mean_and_error(&logs),
            }
        };
        s.structured_fidelity = fid(&structured);
        s.stochastic_fidelity = fid(&stochastic);
        let mut by_side: Vec<(u32, Vec<f64>)> = Vec::new();
        for (r, &side) in results.iter().zip(sides) {
            let times = r.choices.iter().map(|c| c.analysis_ms);
            match by_side.iter_mut().find(|(s, _)| *s == side) {
                Some((_, v)) => v.extend(times),
                None => by_side.push((side, times.collect())),
            }
        }
        by_side.sort_by_key(|(side, _)| *side);
        s.median_ms = by_side
            .into_iter()
            .map(|(side, mut v)| {
                v.sort_by(f64::total_cmp);
                (side, v[v.len() / 2])
            })
            .collect();
        for r in results {
            let label = match &r.entry.families {
                Some(f) => f.join("/"),
                None => format!("({:?})", r.entry.category).to_lowercase(),
            };
            let row = match s.confusion.iter().position(|(l, _)| *l == label) {
                Some(i) => i,
                None => {
                    s.confusion.push((label, Vec::new()));
                    s.confusion.len() - 1
                }
            };
            for c in &r.choices {
                let cells = &mut s.confusion[row].1;
                match cells.iter_mut().find(|(m, _)| *m == c.chosen) {
                    Some((_, n)) => *n += 1,
                    None => cells.push((c.chosen.clone(), 1)),
                }
            }
        }
        s.confusion.sort_by(|a, b| a.0.cmp(&b.0));
        s.specks_clean = Rate::of(
            &results
                .iter()
                .map(|r| {
                    let clean = r
                        .choices
                        .iter()
                        .filter(|c| {
                            speck_ratio(c.render_specks, c.photo_specks, c.pixels) <= SPECK_LIMIT
                        })
                        .count();
                    (clean, r.choices.len())
                })
                .collect::<Vec<_>>(),
        );
        let mut by_model: Vec<(String, Vec<f64>)> = Vec::new();
        for c in results.iter().flat_map(|r| &r.choices) {
            for k in &c.ranking {
                let ratio = speck_ratio(k.specks, c.photo_specks, c.pixels);
                match by_model.iter_mut().find(|(m, _)| *m == k.name) {
                    Some((_, v)) => v.push(ratio),
                    None => by_model.push((k.name.clone(), vec![ratio])),
                }
            }
        }
        by_model.sort_by(|a, b| a.0.cmp(&b.0));
        s.specks_by_model = by_model
            .into_iter()
            .map(|(model, mut v)| {
                v.sort_by(f64::total_cmp);
                SpeckRow {
                    model,
                    renders: v.len(),
                    over_limit: v.iter().filter(|&&x| x > SPECK_LIMIT).count(),
                    median_ratio: median(&v),
                    max_ratio: v.last().copied().unwrap_or(0.0),
                }
            })
            .collect();
        let mut numbers: Vec<usize> = results
            .iter()
            .flat_map(|r| r.choices.iter().map(|c| c.noise_numbers))
            .collect();
        numbers.sort_unstable();
        if let (Some(&least), Some(&most)) = (numbers.first(), numbers.last()) {
            s.noise_numbers = [least, numbers[numbers.len() / 2], most];
        }
        s
    }
}

/// A fidelity's ratios for tables: spectrum, colour, structure, overall.
pub fn ratios(f: &Fidelity) -> [f64; 4] {
    [
        f.spectrum_ratio,
        f.colour_ratio,
        f.structure_ratio,
        overall(f),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn manifest_with_and_without_families() {
        let dev = "file\tcategory\tmaterial\tfamilies\tlicense\n\
                   a.png\tstructured\tbrick wall\tbrick grid\tCC0\n\
                   b.png\tstochastic\tsand\tnoise\tCC0\n";
        let e = parse_manifest(dev).unwrap();
        assert_eq!(e.len(), 2);
        assert_eq!(e[0].category, Category::Structured);
        assert_eq!(e[0].families.as_deref().unwrap(), ["brick", "grid"]);
        assert_eq!(e[1].material, "sand");
        let shipped = "file\tcategory\tmaterial\tlicense\nc.png\tstochastic\tgravel\tCC0\n";
        assert!(parse_manifest(shipped).unwrap()[0].families.is_none());
        for bad in [
            "",
            "file\tmaterial\na.png\tx\n",
            "file\tcategory\tmaterial\na.png\tsoft\tx\n",
            "file\tcategory\tmaterial\tfamilies\na.png\tstructured\tx\tbricks\n",
            "file\tcategory\tmaterial\na.png\tstructured\n",
        ] {
            assert!(parse_manifest(bad).is_err(), "{bad:?}");
        }
    }

    #[test]
    fn folds_are_stable_and_spread() {
        let names: Vec<String> = (0..200).map(|i| format!("photo_{i}.png")).collect();
        let mut counts = [0usize; 4];
        for n in &names {
            let f = fold_of(n, 4);
            assert_eq!(f, fold_of(n, 4));
            counts[f] += 1;
        }
        assert!(counts.iter().all(|&c| (30..=70).contains(&c)), "{counts:?}");
    }

    fn fidelity(halves: f64, ratio: f64) -> Fidelity {
        let d = |v: f64| crate::distance::Distances {
            spectrum_db: v,
            colour: v,
            structure: v,
        };
        Fidelity {
            halves: d(halves),
            synthesis: d(halves * ratio),
            spectrum_ratio: ratio,
            colour_ratio: ratio,
            structure_ratio: ratio,
            floor: d(0.0),
            floor_spectrum_ratio: 0.0,
            floor_colour_ratio: 0.0,
            floor_structure_ratio: 0.0,
            per_patch: [d(halves * ratio); 4],
            repeat: false,
        }
    }

    fn result(file: &str, category: Category, chosen: &str, auto: f64, noise: f64) -> PhotoResult {
        let halves = if auto.is_finite() { 1.0 } else { 0.0 };
        PhotoResult {
            entry: Entry {
                file: file.into(),
                category,
                material: "m".into(),
                families: Some(vec![if category == Category::Structured {
                    "brick".into()
                } else {
                    "noise".into()
                }]),
            },
            choices: PATCHES
                .iter()
                .map(|p| PatchChoice {
                    patch: p,
                    chosen: chosen.into(),
                    top3: vec![chosen.into(), "brick".into(), "noise".into()],
                    analysis_ms: 100.0,
                    ranking: vec![Candidate {
                        name: chosen.into(),
                        distance: 1.0,
                        score: 1.0,
                        retrieval: 1.0,
                        refined: None,
                        // 2.5× the photo's specks on the structured photos' candidates.
                        specks: if category == Category::Structured {
                            0.01
                        } else {
                            0.004
                        },
                        cues: [0.0; crate::cues::CUES],
                        classifier_distances: Default::default(),
                    }],
                    photo_specks: 0.004,
                    // The chosen synthesis: past the limit on the first photo only.
                    render_specks: if file == "a.png" { 0.01 } else { 0.004 },
                    pixels: 10_000,
                    photo_cues: [0.0; crate::cues::CUES],
                    noise_numbers: if file == "a.png" { 60 } else { 100 },
                    classifier: Vec::new(),
                    classifier_distances: vec![1.0],
                    noise_render_margin: 0.0,
                    nearer_render_margin: 0.0,
                    nearer_render_distances: None,
                })
                .collect(),
            auto: fidelity(halves, if auto.is_finite() { auto } else { 1e9 }),
            noise: fidelity(halves, if noise.is_finite() { noise } else { 1e9 }),
        }
    }

    #[test]
    fn the_summary_counts_labels_and_leaves_out_undefined_fidelity() {
        let results = [
            result("a.png", Category::Structured, "brick", 1.2, 1.5),
            result("b.png", Category::Structured, "grid", 1.4, 1.4),
            // Paired quadrants with the same pixels: no fidelity, still a choice.
            result(
                "c.png",
                Category::Structured,
                "brick",
                f64::INFINITY,
                f64::INFINITY,
            ),
            result("d.png", Category::Stochastic, "noise", 1.1, 1.1),
            // A family on a stochastic photo, farther than the noise model: not served well.
            result("e.png", Category::Stochastic, "ridged", 1.3, 1.2),
        ];
        let s = Summary::of(&results, &[128; 5]);
        assert_eq!(
            (s.structured_labelled.hits, s.structured_labelled.total),
            (8, 12)
        );
        assert_eq!(s.structured_top3.hits, 12);
        assert_eq!((s.stochastic_ok.hits, s.stochastic_ok.total), (4, 8));
        let f = s.structured_fidelity;
        assert_eq!((f.photos, f.undefined), (2, 1));
        assert!((f.difference.0 - (-0.15)).abs() < 1e-9, "{f:?}");
        assert!((f.median_difference - (-0.15)).abs() < 1e-9, "{f:?}");
        assert!(
            (f.log_ratio.0 - 0.5 * (1.2f64 / 1.5).ln()).abs() < 1e-9,
            "{f:?}"
        );
        assert_eq!(s.median_ms, vec![(128, 100.0)]);
        let brick = &s.confusion.iter().find(|(l, _)| l == "brick").unwrap().1;
        assert!(
            brick.contains(&("brick".to_string(), 8)) && brick.contains(&("grid".to_string(), 4))
        );
        assert_eq!((s.specks_clean.hits, s.specks_clean.total), (16, 20));
        let row = |m: &str| s.specks_by_model.iter().find(|r| r.model == m).unwrap();
        let brick = row("brick");
        assert_eq!((brick.renders, brick.over_limit), (8, 8));
        assert!((brick.max_ratio - 101.0 / 41.0).abs() < 1e-9, "{brick:?}");
        assert_eq!((row("noise").renders, row("noise").over_limit), (4, 0));
        assert!((row("noise").median_ratio - 1.0).abs() < 1e-12);
        // The noise model's numbers: 60 on the first photo's four patches, 100 elsewhere.
        assert_eq!(s.noise_numbers, [60, 100, 100]);
    }

    #[test]
    fn rates_and_errors_count_photos_as_the_samples() {
        let r = Rate::of(&[(4, 4), (0, 4), (2, 4)]);
        assert_eq!((r.hits, r.total), (6, 12));
        assert!((r.fraction() - 0.5).abs() < 1e-12);
        // Per-photo rates 1, 0, 0.5: sd 0.5, over √3.
        assert!((r.standard_error - 0.5 / 3f64.sqrt()).abs() < 1e-12);
        assert_eq!(mean_and_error(&[2.0]), (2.0, 0.0));
    }
}
