#!/usr/bin/env python3
r"""Other classifiers and other features for the family classifier, measured outside Rust
(laboratory; docs/devset.md, "A two-class gate, the noise model's margin, a floor on the
lattices' scale, other classifiers and features" and "Scattering features").

The product's classifier is Fisher's linear discriminant (`analyzer/examples/corpus_lab/`,
`proctex::family_classifier`). This script reads the features `corpus_lab eval` writes with
`CORPUS_LAB_FEATURES=PATH` (one row per training quadrant and development patch) and scores
other classifiers the same way `corpus_lab eval` scores the discriminant: trained on the corpus
alone, each development patch's nearest family (the most probable class other than noise)
labelled or not, the first class, the first three, and stochastic patches whose first class is
noise. The development set is never trained on and no setting is chosen on it (each classifier
is run at library defaults or one fixed regularisation).

  classifier_lab.py classifiers FEATURES.tsv [EXTRA.tsv [alone]]   (EXTRA: more features per row, as
      `lbp` writes; `alone`: EXTRA's features without FEATURES')
  classifier_lab.py lbp FEATURES.tsv CORPUS_DIR DEV_DIR OUT.tsv   (rotation-invariant uniform
      local binary patterns, Ojala et al. 2002, of each row's quadrant: P=8 R=1, 2; P=16 R=4, 8;
      and P=8 R=1 on the quadrant reduced 2× and 4×; square roots of the histograms)
  classifier_lab.py phases FEATURES.tsv CORPUS_DIR DEV_DIR OUT.tsv   (the units of each quadrant's
      bright and dark phases: the luminance smoothed by a Gaussian of sigma 1, 2 and 4, split at
      its local mean (a wrapped box of a quarter of the side); per phase, the square root of its
      components' area-weighted mean area over the side, their count per 10^4 pixels (log1p),
      the largest one's share, their area-weighted elongation (half the log ratio of their
      second moments' eigenvalues, components of at least 8 pixels) and the phase's share)
  classifier_lab.py unit_colours FEATURES.tsv CORPUS_DIR DEV_DIR OUT.tsv   (the same phases'
      components of at least 16 pixels: the log ratio of their mean colours' variance between
      components to the colour variance within them, of the red and blue channels' part of the
      former, and their count per 10^4 pixels)
  classifier_lab.py gate RUN.jsonl DUMP   (a two-class discriminant as the gate between the noise
      model and the families: DUMP is `corpus_lab eval`'s stderr with `CORPUS_LAB_DUMP=1`, trained
      on the labels with every family renamed `brick` (one structured class:
      awk -F'\t' 'BEGIN{OFS="\t"} !/^#/ && NF {if ($2 != "noise") $2 = "brick"; print}' LABELS...);
      where the run chose the noise model and the patch's margin (the noise class's distance minus
      the structured class's) exceeds t, the classifier's nearest family of the run instead; t
      chosen on 4 folds by photo as the most structured patches labelled among those keeping
      >= 95 % of the stochastic patches served, a switched stochastic patch counted as not served)
  classifier_lab.py scattering FEATURES.tsv CORPUS_DIR DEV_DIR OUT.tsv [128]   (rotation-invariant
      scattering of each quadrant's luminance, Bruna & Mallat 2013, Sifre & Mallat 2013: Morlet
      wavelets of 5 scales and 8 orientations, first and second order averaged over space;
      `scattering_features`; about 0.4 s a quadrant, 25 minutes for the four batches on 2 cores;
      with 128: the quadrant reduced to 128 pixels, 4 scales, 5 minutes)
  classifier_lab.py renders DEV_DIR PROCTEX OUT_DIR MODEL [SEED]   (a model's render of every
      development patch, `proctex synth --crop QUADRANT --model MODEL --seed SEED`; MODEL
      `nearest=RUN.jsonl`: the run's classifier's nearest family of each patch)
  classifier_lab.py render_scattering OUT_DIR RENDERS.tsv [128]   (those renders' scattering)
  classifier_lab.py scattering_gate RUN.jsonl FEATURES.tsv SCATTERING.tsv RENDERS.tsv[,RENDERS2.tsv…]
      (the scattering's structured-vs-noise log odds, of the patch and of the patch minus its noise
      render's, as `gate`'s margin; trained on the corpus alone; t chosen on 4 folds as `gate`)
  classifier_lab.py render_gate RUN.jsonl FEATURES.tsv SCATTERING.tsv NOISE.tsv[,NOISE2.tsv…] FAMILY.tsv
      (the photo's scattering distance to its noise render minus that to its nearest family's
      render as `gate`'s margin; the same size's features throughout)

Needs numpy, scikit-learn and (for `lbp`, `phases`, `unit_colours`, `scattering`) scikit-image,
SciPy and Pillow: `pip install scikit-learn scikit-image scipy pillow`.
"""
import json
import sys
import warnings

import numpy as np

warnings.filterwarnings("ignore")


def load(path, extra=None):
    ext = {}
    if extra:
        for line in open(extra):
            t = line.rstrip("\n").split("\t")
            ext[(t[0], t[1], t[2])] = [float(v) for v in t[3:]]
    train, dev = [], []
    for line in open(path):
        t = line.rstrip("\n").split("\t")
        x = [float(v) for v in t[4:]] + ext.get((t[0], t[1], t[2]), [])
        (train if t[0] == "train" else dev).append((t[3], np.array(x)))
    return train, dev


def score(model, train, dev, name):
    x = np.array([r[1] for r in train])
    y = np.array([r[0] for r in train])
    model.fit(x, y)
    classes = list(model.classes_)
    family = first = top3 = structured = stochastic = kept = 0
    for (labels, _), p in zip(dev, model.predict_proba(np.array([r[1] for r in dev]))):
        labels = labels.split("/")
        order = [classes[i] for i in np.argsort(-p)]
        if labels == ["noise"]:
            stochastic += 1
            kept += order[0] == "noise"
        else:
            structured += 1
            family += next(c for c in order if c != "noise") in labels
            first += order[0] in labels
            top3 += any(c in labels for c in order[:3])
    print(f"{name:32s} nearest family {family}/{structured}, first {first}, top three {top3}; "
          f"stochastic -> noise {kept}/{stochastic}", flush=True)


def classifiers(path, extra=None, alone=None):
    from sklearn.discriminant_analysis import LinearDiscriminantAnalysis
    from sklearn.ensemble import (ExtraTreesClassifier, HistGradientBoostingClassifier,
                                  RandomForestClassifier)
    from sklearn.linear_model import LogisticRegression
    from sklearn.pipeline import make_pipeline
    from sklearn.preprocessing import StandardScaler
    from sklearn.svm import SVC
    train, dev = load(path, extra)
    if alone == "alone":  # EXTRA's features without FEATURES'
        width = len(load(path)[0][0][1])
        train, dev = ([(y, x[width:]) for y, x in rows] for rows in (train, dev))
    models = {
        "LDA, shrinkage (Ledoit-Wolf)": make_pipeline(
            StandardScaler(), LinearDiscriminantAnalysis(solver="lsqr", shrinkage="auto")),
        "logistic regression C=1": make_pipeline(StandardScaler(),
                                                 LogisticRegression(C=1, max_iter=5000)),
        "logistic regression C=0.1": make_pipeline(StandardScaler(),
                                                   LogisticRegression(C=0.1, max_iter=5000)),
        "random forest 500": RandomForestClassifier(500, n_jobs=2, random_state=0),
        "random forest 500, balanced": RandomForestClassifier(
            500, n_jobs=2, random_state=0, class_weight="balanced"),
        "extra trees 500": ExtraTreesClassifier(500, n_jobs=2, random_state=0),
        "gradient boosting (histogram)": HistGradientBoostingClassifier(random_state=0),
        "SVM, RBF, C=3": make_pipeline(StandardScaler(),
                                       SVC(C=3, probability=True, random_state=0)),
    }
    for name, model in models.items():
        score(model, train, dev, name)


QUADRANT_CORNERS = [(0, 0), (1, 0), (0, 1), (1, 1)]  # TL, TR, BL, BR: the lab's order


def reduced(im, colour=False):
    """A PIL image's luminance (RGB in 0–1 with `colour`), reduced to at most 256 pixels a side
    as the ranking reduces a patch (retrieve::RANK_SIZE)."""
    from PIL import Image
    if max(im.size) > 256:
        s = 256 / max(im.size)
        im = im.resize((round(im.size[0] * s), round(im.size[1] * s)), Image.BOX)
    rgb = np.asarray(im.convert("RGB"), dtype=np.float64)
    return rgb / 255 if colour else rgb @ [0.2126, 0.7152, 0.0722]


def quadrants(file, colour=False):
    """A texture's four quadrants (`QUADRANT_CORNERS`), each `reduced`."""
    from PIL import Image
    im = Image.open(file).convert("RGB")
    w, h = im.size
    for qx, qy in QUADRANT_CORNERS:
        yield reduced(im.crop((qx * (w // 2), qy * (h // 2), (qx + 1) * (w // 2),
                               (qy + 1) * (h // 2))), colour)


def write_features(path, corpus_dir, dev_dir, out, features, colour=False):
    """`features` of every quadrant of the textures and photos that FEATURES names."""
    done = set()
    with open(out, "w") as o:
        for line in open(path):
            t = line.split("\t", 3)
            if (t[0], t[1]) in done:
                continue
            done.add((t[0], t[1]))
            folder = corpus_dir if t[0] == "train" else dev_dir
            for q, g in enumerate(quadrants(f"{folder}/{t[1]}", colour)):
                o.write("\t".join([t[0], t[1], str(q)] + ["%.6g" % v for v in features(g)]) + "\n")


def lbp(path, corpus_dir, dev_dir, out):
    from skimage.feature import local_binary_pattern

    def histogram(g, p, r):
        c = local_binary_pattern(g, p, r, "uniform").astype(int).ravel()
        h = np.bincount(c, minlength=p + 2)[:p + 2].astype(float)
        return list(np.sqrt(h / h.sum()))

    def features(g):
        f = []
        for p, r in [(8, 1), (8, 2), (16, 4), (16, 8)]:
            f += histogram(g, p, r)
        for k in (2, 4):
            h, w = g.shape
            f += histogram(g[:h // k * k, :w // k * k].reshape(h // k, k, w // k, k).mean((1, 3)),
                           8, 1)
        return f

    write_features(path, corpus_dir, dev_dir, out, features)


def bright_phases(g):
    """The luminance `g` smoothed by a Gaussian of sigma 1, 2 and 4, each split at its local mean
    (a wrapped box of a quarter of the side): where it is brighter."""
    from scipy import ndimage
    for sigma in (1, 2, 4):
        smooth = ndimage.gaussian_filter(g, sigma, mode="wrap")
        yield smooth > ndimage.uniform_filter(smooth, max(3, min(g.shape) // 4), mode="wrap")


def phases(path, corpus_dir, dev_dir, out):
    from scipy import ndimage

    def stats(mask):
        labels, n = ndimage.label(mask)
        if n == 0:
            return [0, 0, 0, 0, 0]
        areas = np.bincount(labels.ravel())[1:].astype(float)
        size = np.sqrt((areas ** 2).sum() / areas.sum()) / mask.shape[0]
        count = np.log1p(n / mask.size * 1e4)
        largest = areas.max() / areas.sum()
        ys, xs = np.nonzero(labels > 0)
        of = labels[ys, xs]
        elongation, weight = [], []
        for k in (np.nonzero(areas >= 8)[0] + 1)[:400]:
            sel = of == k
            ev = np.linalg.eigvalsh(np.cov(np.vstack([xs[sel], ys[sel]])))
            elongation.append(np.log((ev[1] + 1e-3) / (ev[0] + 1e-3)) / 2)
            weight.append(sel.sum())
        elongated = np.average(elongation, weights=weight) if weight else 0
        return [size, count, largest, elongated, mask.mean()]

    def features(g):
        f = []
        for bright in bright_phases(g):
            f += stats(bright) + stats(~bright)
        return f

    write_features(path, corpus_dir, dev_dir, out, features)


def unit_colours(path, corpus_dir, dev_dir, out):
    from scipy import ndimage

    def features(rgb):
        g = rgb @ [0.2126, 0.7152, 0.0722]
        f = []
        for bright in bright_phases(g):
            for mask in (bright, ~bright):
                labels, n = ndimage.label(mask)
                index = np.arange(1, n + 1)
                area = ndimage.sum(np.ones_like(g), labels, index)
                keep = index[area >= 16]
                if len(keep) < 2:
                    f += [0, 0, 0]
                    continue
                a = area[keep - 1]
                between, within = [], []
                for c in range(3):
                    mean = ndimage.mean(rgb[..., c], labels, keep)
                    between.append(np.average((mean - np.average(mean, weights=a)) ** 2, weights=a))
                    within.append(np.average(ndimage.variance(rgb[..., c], labels, keep), weights=a))
                between = np.array(between)
                f += [np.log((between.sum() + 1e-6) / (sum(within) + 1e-6)),
                      np.log((between[0] + between[2] + 1e-6) / (between.sum() + 1e-6)),
                      np.log(len(keep) / mask.size * 1e4)]
        return f

    write_features(path, corpus_dir, dev_dir, out, features, colour=True)


SCATTERING_L = 8  # orientations


def morlet_bank(n, scales):
    """Morlet wavelets in the frequency domain on an n x n grid (Bruna & Mallat 2013): scale j
    has envelope width 0.8 * 2^j px and centre frequency 3*pi/4 / 2^j, orientation l is
    pi * l / L; the envelope is narrower across the orientation by L/4 (as kymatio's slant) and
    the wavelet has no DC (the Gaussian's share at zero subtracted)."""
    from scipy import fft
    w = 2 * np.pi * fft.fftfreq(n)
    wy, wx = np.meshgrid(w, w, indexing="ij")
    bank = {}
    for j in range(scales):
        sigma, xi = 0.8 * 2 ** j, 3 * np.pi / 4 / 2 ** j
        for l in range(SCATTERING_L):
            th = np.pi * l / SCATTERING_L
            cx, cy = xi * np.cos(th), xi * np.sin(th)

            def envelope(ax, ay):
                u = ax * np.cos(th) + ay * np.sin(th)
                v = -ax * np.sin(th) + ay * np.cos(th)
                return np.exp(-sigma ** 2 * (u ** 2 + (v * SCATTERING_L / 4) ** 2) / 2)
            beta = envelope(np.array(-cx), np.array(-cy))
            psi = envelope(wx - cx, wy - cy) - beta * envelope(wx, wy)
            bank[(j, l)] = psi.astype(np.complex64)
    return bank


def scattering_features(g, half=False, banks={}):
    """Rotation-invariant scattering of a luminance image (its square top-left part, normalised
    to zero mean and unit variance; with `half`, first reduced 2x by 2x boxes to at most 128 pixels
    a side and 4 scales instead of 5): log of the first order's spatial means averaged over
    orientations per scale, the first two orientation harmonics' magnitudes relative to it, and
    the second order's log ratio to the first, ||x * psi_j1,l1| * psi_j2,l2| averaged over
    space and over l1 at each orientation difference l2 - l1 (Sifre & Mallat 2013): 5 + 10 + 80
    numbers (with `half` 4 + 8 + 48)."""
    from scipy import fft
    g = np.asarray(g, dtype=np.float64)
    if half and min(g.shape) > 128:
        h, w = g.shape
        g = g[:h // 2 * 2, :w // 2 * 2].reshape(h // 2, 2, w // 2, 2).mean((1, 3))
    n = min(g.shape)
    g = g[:n, :n]
    g = (g - g.mean()) / (g.std() + 1e-6)
    J, L = (4 if half else 5), SCATTERING_L
    if (n, J) not in banks:
        banks[(n, J)] = morlet_bank(n, J)
    bank = banks[(n, J)]
    x = fft.fft2(g.astype(np.complex64))
    s1, s2 = np.zeros((J, L)), np.zeros((J, J, L))
    for j1 in range(J):
        for l1 in range(L):
            u1 = np.abs(fft.ifft2(x * bank[(j1, l1)]))
            s1[j1, l1] = u1.mean()
            if j1 < J - 1:
                u1 = fft.fft2(u1.astype(np.complex64))
            for j2 in range(j1 + 1, J):
                for l2 in range(L):
                    s2[j1, j2, (l2 - l1) % L] += np.abs(fft.ifft2(u1 * bank[(j2, l2)])).mean() / L
    first = s1.mean(1)
    f = list(np.log(first))
    for j in range(J):
        h = np.fft.fft(s1[j])
        f += [abs(h[1]) / h[0].real, abs(h[2]) / h[0].real]
    for j1 in range(J):
        for j2 in range(j1 + 1, J):
            f += list(np.log(s2[j1, j2] / first[j1]))
    return f


def scattering(path, corpus_dir, dev_dir, out, size="256"):
    write_features(path, corpus_dir, dev_dir, out,
                   lambda g: scattering_features(g, half=size == "128"))


def renders(dev_dir, proctex, out_dir, model="noise", seed="1"):
    """A model's render of every development patch, `proctex synth --crop QUADRANT --model M
    --seed SEED` (two at a time), as OUT_DIR/PHOTO.Q.png, Q in the lab's order: M is MODEL, or
    with MODEL `nearest=RUN.jsonl` the run's classifier's nearest family for that patch (the
    family the render-null rule would put first)."""
    import os
    from concurrent.futures import ThreadPoolExecutor
    import subprocess
    from PIL import Image
    nearest = {}
    if model.startswith("nearest="):
        for photo, _, c in run_rows(model[len("nearest="):]):
            nearest[(photo, QUADRANTS.index(c["patch"]))] = next(
                k for k in c["classifier"] if k != "noise")
    jobs = []
    for line in open(f"{dev_dir}/manifest.tsv"):
        name = line.split("\t")[0]
        if line.startswith("#") or not name.endswith((".png", ".jpg")):
            continue
        w, h = Image.open(f"{dev_dir}/{name}").size
        for q, (qx, qy) in enumerate(QUADRANT_CORNERS):
            jobs.append([proctex, "synth", f"{dev_dir}/{name}", "--crop",
                         f"{qx * (w // 2)},{qy * (h // 2)},{w // 2},{h // 2}",
                         "--model", nearest.get((name, q), model), "--seed", seed,
                         "-o", os.path.join(out_dir, f"{name}.{q}.png")])
    with ThreadPoolExecutor(2) as pool:
        for r in pool.map(lambda j: subprocess.run(j, capture_output=True), jobs):
            r.check_returncode()


def render_scattering(render_dir, out, size="256"):
    """`scattering_features` of the renders `renders` wrote (each `reduced` as a patch is), one
    row per development patch."""
    import os
    from PIL import Image
    with open(out, "w") as o:
        for f in sorted(os.listdir(render_dir)):
            g = reduced(Image.open(os.path.join(render_dir, f)))
            row = ["%.6g" % v for v in scattering_features(g, size == "128")]
            o.write("\t".join(["dev", f[:-6], f[-5]] + row) + "\n")


QUADRANTS = ["top-left", "top-right", "bottom-left", "bottom-right"]  # the lab's order


def run_rows(run):
    """The run's patches as (photo, its labels, the choice with `served` added)."""
    from devset_occam_cv import patch_overall
    rows = []
    for line in open(run):
        if line.startswith('{"photo"'):
            p = json.loads(line)["photo"]
            for i, c in enumerate(p["choices"]):
                # Served by the run: the noise model, or a family no farther than it.
                c = dict(c, served=c["chosen"] == "noise"
                         or patch_overall(p["auto"], i) <= patch_overall(p["noise"], i))
                rows.append((p["entry"]["file"], p["entry"]["families"], c))
    return rows


def gate_tally(rows, margin, t):
    """Structured patches labelled and stochastic patches served when, where the run chose the
    noise model and the patch's margin exceeds t, the run's classifier's nearest family is
    chosen instead (a switched stochastic patch counted as not served)."""
    labelled = served = 0
    for photo, labels, c in rows:
        chosen = c["chosen"]
        if chosen == "noise" and margin[(photo, c["patch"])] > t:
            chosen = next(k for k in c["classifier"] if k != "noise")
        if labels == ["noise"]:
            served += chosen == c["chosen"] and c["served"]
        else:
            labelled += chosen in labels
    return labelled, served


def gate_cv(rows, margin, grid):
    """t chosen on 4 folds by photo as the most structured patches labelled among those keeping
    >= 95 % of the other folds' stochastic patches served (ties: the larger t); the held-out
    folds' counts and the four t."""
    from devset_occam_cv import fold_of
    held, chosen = [0, 0], []
    for f in range(4):
        train = [r for r in rows if fold_of(r[0], 4) != f]
        stochastic = sum(r[1] == ["noise"] for r in train)
        ok = [(r, t) for r, t in ((gate_tally(train, margin, t), t) for t in grid)
              if r[1] >= 0.95 * stochastic]
        t = max(ok)[1]
        chosen.append(t)
        a, b = gate_tally([r for r in rows if fold_of(r[0], 4) == f], margin, t)
        held = [held[0] + a, held[1] + b]
    return held, chosen


def patch_rows(path):
    """A `render_scattering` file as {(photo, quadrant name): its numbers}."""
    out = {}
    for line in open(path):
        t = line.rstrip("\n").split("\t")
        out[(t[1], QUADRANTS[int(t[2])])] = np.array([float(v) for v in t[3:]])
    return out


def midpoints(margin):
    """The thresholds worth trying for `margin`: between each two of its values, and infinity."""
    at = sorted(set(margin.values()))
    return [(a + b) / 2 for a, b in zip(at, at[1:])] + [float("inf")]


def gate(run, dump):
    margin, seen = {}, {}
    for line in open(dump):
        if line.startswith("dump\t"):
            t = line.rstrip("\n").split("\t")
            k = seen.get(t[1], 0)
            seen[t[1]] = k + 1
            margin[(t[1], QUADRANTS[k])] = float(t[4])
    rows = run_rows(run)
    grid = [x / 4 for x in range(-40, 41)] + [float("inf")]
    print("the run: labelled %d, served %d" % gate_tally(rows, margin, float("inf")))
    for t in [-4, -2, 0, 1, 2, 3]:
        print(f"t {t}: labelled %d, served %d" % gate_tally(rows, margin, t))
    held, chosen = gate_cv(rows, margin, grid)
    print(f"held out (t chosen on the other folds {chosen}): labelled {held[0]}, served {held[1]}")



def scattering_gate(run, features, scattering_tsv, renders_tsv):
    """The scattering features' structured-vs-noise log odds as the gate over the run's choice
    (`gate_tally`): of the photo's patch alone, and of the patch minus the noise model's render
    of it (the render as the classifier's null, as the product's `RENDER_NULL_MARGIN` rule).
    Trained on the corpus alone (every family one structured class, or the eight classes with
    P(noise)); t chosen on 4 folds by photo (`gate_cv`)."""
    from sklearn.discriminant_analysis import LinearDiscriminantAnalysis
    from sklearn.linear_model import LogisticRegression
    from sklearn.metrics import roc_auc_score
    from sklearn.pipeline import make_pipeline
    from sklearn.preprocessing import StandardScaler
    rows = run_rows(run)
    with_scattering = load(features, scattering_tsv)
    width = len(load(features)[0][0][1])
    train = [(y, x[width:]) for y, x in with_scattering[0]]
    dev = np.array([x[width:] for _, x in with_scattering[1]])
    keys = [(t[1], QUADRANTS[int(t[2])]) for t in (line.split("\t", 3) for line in open(features))
            if t[0] == "dev"]
    renders = [np.array([r[k] for k in keys]) for r in map(patch_rows, renders_tsv.split(","))]
    x, y = np.array([r[1] for r in train]), np.array([r[0] for r in train])
    structured = [labels != ["noise"] for _, labels, _ in rows]
    print("the run: labelled %d, served %d" % gate_tally(rows, {k: 0 for k in keys}, float("inf")))
    models = {
        "LDA, shrinkage": lambda: make_pipeline(
            StandardScaler(), LinearDiscriminantAnalysis(solver="lsqr", shrinkage="auto")),
        "logistic regression C=0.1": lambda: make_pipeline(
            StandardScaler(), LogisticRegression(C=0.1, max_iter=5000)),
    }
    for name, model in models.items():
        for two in (True, False):
            m = model().fit(x, np.where(y == "noise", "noise", "structured") if two else y)
            noise = list(m.classes_).index("noise")

            def odds(a):
                p = m.predict_proba(a)[:, noise]
                return np.log(1 - p + 1e-6) - np.log(p + 1e-6)
            beyond = odds(dev) - np.mean([odds(r) for r in renders], 0)
            for null, margin in (("photo", odds(dev)), ("photo - render", beyond)):
                margin = dict(zip(keys, margin.tolist()))
                held, chosen = gate_cv(rows, margin, midpoints(margin))
                auc = roc_auc_score(structured, [margin[(p, c["patch"])] for p, _, c in rows])
                classes = "two classes" if two else "eight classes"
                print(f"{name}, {classes}, {null}: AUC {auc:.3f}, "
                      f"held out labelled {held[0]}, served {held[1]} (t "
                      + ", ".join("%.2f" % t for t in chosen) + ")")


def render_gate(run, features, scattering_tsv, noise_tsv, family_tsv):
    """Which render the photo is nearer to in scattering space, the noise model's or the
    classifier's nearest family's (`renders`; analysis by synthesis, as Bourque & Dudek and the
    two-tone paper choose, with the scattering's distance instead of the texture distance), as
    `gate`'s margin: |photo - noise render| - |photo - family render|, the features standardised
    by the corpus's means and deviations (`standardised`) or projected on its eight-class
    discriminant's axes (`discriminant`); t chosen on 4 folds (`gate_cv`). NOISE_TSV may be
    several files, comma-separated, one per seed: each is scored on its own."""
    from sklearn.discriminant_analysis import LinearDiscriminantAnalysis
    from sklearn.metrics import roc_auc_score
    rows = run_rows(run)
    with_scattering = load(features, scattering_tsv)
    width = len(load(features)[0][0][1])
    x = np.array([r[1][width:] for r in with_scattering[0]])
    y = np.array([r[0] for r in with_scattering[0]])
    keys = [(t[1], QUADRANTS[int(t[2])]) for t in (line.split("\t", 3) for line in open(features))
            if t[0] == "dev"]
    photo = dict(zip(keys, [r[1][width:] for r in with_scattering[1]]))
    family = patch_rows(family_tsv)
    mean, sd = x.mean(0), x.std(0) + 1e-9
    lda = LinearDiscriminantAnalysis(solver="eigen", shrinkage="auto").fit((x - mean) / sd, y)
    spaces = {"standardised": lambda v: (v - mean) / sd,
              "discriminant": lambda v: lda.transform(((v - mean) / sd)[None])[0]}
    structured = [labels != ["noise"] for _, labels, _ in rows]
    print("the run: labelled %d, served %d" % gate_tally(rows, {k: 0 for k in keys}, float("inf")))
    for noise_tsv_one in noise_tsv.split(","):
        noise = patch_rows(noise_tsv_one)
        for name, space in spaces.items():
            margin = {k: float(np.linalg.norm(space(photo[k]) - space(noise[k]))
                               - np.linalg.norm(space(photo[k]) - space(family[k]))) for k in keys}
            held, chosen = gate_cv(rows, margin, midpoints(margin))
            auc = roc_auc_score(structured, [margin[(p, c["patch"])] for p, _, c in rows])
            print(f"{noise_tsv_one}, {name}: AUC {auc:.3f}, held out labelled {held[0]}, served "
                  f"{held[1]} (t " + ", ".join("%.2f" % t for t in chosen) + ")")


if __name__ == "__main__":
    if len(sys.argv) >= 3 and sys.argv[1] == "classifiers":
        classifiers(*sys.argv[2:5])
    elif len(sys.argv) == 4 and sys.argv[1] == "gate":
        gate(*sys.argv[2:])
    elif len(sys.argv) == 6 and sys.argv[1] == "lbp":
        lbp(*sys.argv[2:])
    elif len(sys.argv) == 6 and sys.argv[1] == "phases":
        phases(*sys.argv[2:])
    elif len(sys.argv) == 6 and sys.argv[1] == "unit_colours":
        unit_colours(*sys.argv[2:])
    elif len(sys.argv) in (6, 7) and sys.argv[1] == "scattering":
        scattering(*sys.argv[2:])
    elif len(sys.argv) in (5, 6, 7) and sys.argv[1] == "renders":
        renders(*sys.argv[2:])
    elif len(sys.argv) in (4, 5) and sys.argv[1] == "render_scattering":
        render_scattering(*sys.argv[2:])
    elif len(sys.argv) == 7 and sys.argv[1] == "render_gate":
        render_gate(*sys.argv[2:])
    elif len(sys.argv) == 6 and sys.argv[1] == "scattering_gate":
        scattering_gate(*sys.argv[2:])
    else:
        sys.exit(__doc__)
