#!/usr/bin/env python3
"""The weight of the family classifier's opinion in the order of the fitted families
(retrieve::CLASSIFIER_WEIGHT), cross-validated on the development set, offline.

The ranking (retrieve::Suggester::ranked) fits the classifier's first three families and orders
them by score = 0.1 structure + 0.9 texture distance + λ · (d − d0) / 2 · self distance + margin,
d the family's squared class distance in the classifier (d0 the nearest of the three); the noise
model comes first when its texture distance is below the best family's plus the margin
(NOISE_MODEL_MARGIN × self distance), unless the photo has a dark network
(DARK_NETWORK_SKEWNESS: then the best family). Every number is in the run's JSON (`ranking`,
`classifier`, `classifier_distances`, `photo_cues`), so another λ needs no new analysis. With
--kappa the noise model's comparison also gains κ · (d_noise − d_best) / 2 (the classifier's
noise class; measured, not kept).

Protocol: 4 folds by photo (devset::fold_of); for each held-out fold the λ (and κ) with the most
structured patches labelled on the other folds among those keeping >= 95 % of their stochastic
patches served (ties: more served, then the smaller weight), scored on the held-out fold. A
stochastic patch counts as served when the noise model is first, or the family the run chose
and measured no farther than the noise model (a family the run did not choose: not served,
conservatively).

Usage: tools/devset_classifier_weight_cv.py RUN.jsonl [--current L] [--kappa]
  --current  the λ the run was made with (its scores include the term; default 0.02)
"""
import json
import sys

from devset_occam_cv import fold_of, patch_overall, ranking_margin, ranking_rows

SKEWNESS = 7  # cues::CUE_NAMES index of "skewness"
DARK_NETWORK_SKEWNESS = -0.599
NOISE_MODEL_MARGIN = 0.2
FITTED = 3  # retrieve::RENDER_ORDERED
FOLDS = 4
GRID = [0, 0.005, 0.01, 0.015, 0.02, 0.03, 0.05, 0.07, 0.1, 0.2, 0.5, 1, 2, 5, 100]


def patches(photos, current):
    out = []
    for p, i, c, noise, fams in ranking_rows(photos):
        e = p["entry"]
        cd = dict(zip(c["classifier"], c["classifier_distances"]))
        first = [n for n in c["classifier"] if n != "noise"][:FITTED]
        margin = ranking_margin(fams)
        u = margin / NOISE_MODEL_MARGIN
        d0 = min(cd[n] for n in first)
        fitted = {r["name"]: dict(texture=r["distance"],
                                  blend=r["score"] - margin - current * (cd[r["name"]] - d0) / 2 * u)
                  for r in fams if r["name"] in first}
        family_ok = (c["chosen"] != "noise"
                     and patch_overall(p["auto"], i) <= patch_overall(p["noise"], i))
        out.append(dict(file=e["file"], category=e["category"], labels=e["families"] or [],
                        fitted=fitted, cd=cd, d0=d0, u=u, noise_d=noise["distance"],
                        chosen=c["chosen"], family_ok=family_ok,
                        dark=c["photo_cues"][SKEWNESS] < DARK_NETWORK_SKEWNESS))
    return out


def choose(pt, lam, kappa=0.0):
    u, cd = pt["u"], pt["cd"]
    best = min(pt["fitted"], key=lambda n: pt["fitted"][n]["blend"] / u + lam * (cd[n] - pt["d0"]) / 2)
    if pt["dark"]:
        return best
    gain = (pt["noise_d"] - pt["fitted"][best]["texture"]) / u - NOISE_MODEL_MARGIN
    gain += kappa * (cd["noise"] - cd[best]) / 2
    return best if gain > 0 else "noise"


def tally(pts, lam, kappa=0.0):
    lab = ns = served = nt = 0
    for pt in pts:
        c = choose(pt, lam, kappa)
        if pt["category"] == "structured":
            ns += 1
            lab += c in pt["labels"]
        else:
            nt += 1
            served += c == "noise" or (c == pt["chosen"] and pt["family_ok"])
    return lab, ns, served, nt


def pick(pts, kappas):
    best = None
    for lam in GRID:
        for kappa in kappas:
            lab, ns, served, nt = tally(pts, lam, kappa)
            key = (served >= 0.95 * nt, lab, served, -lam, -kappa)
            if best is None or key > best[0]:
                best = (key, lam, kappa)
    return best[1], best[2]


def main():
    args = sys.argv[1:]
    current = float(args[args.index("--current") + 1]) if "--current" in args else 0.02
    kappas = GRID if "--kappa" in args else [0.0]
    photos = [json.loads(l)["photo"] for l in open(args[0]) if '"photo"' in l]
    pts = patches(photos, current)
    agree = sum(choose(pt, current) == pt["chosen"] for pt in pts)
    print(f"{len(photos)} photos, {len(pts)} patches; the numbers reproduce {agree}/{len(pts)} "
          f"choices at λ {current}")
    print("whole set (for reading, not for choosing):")
    for lam in GRID:
        lab, ns, served, nt = tally(pts, lam)
        print(f"  λ {lam:6}: structured labelled {lab}/{ns}, stochastic served {served}/{nt}")
    pooled = [0, 0, 0, 0]
    for k in range(FOLDS):
        train = [pt for pt in pts if fold_of(pt["file"], FOLDS) != k]
        test = [pt for pt in pts if fold_of(pt["file"], FOLDS) == k]
        lam, kappa = pick(train, kappas)
        t = tally(test, lam, kappa)
        pooled = [a + b for a, b in zip(pooled, t)]
        print(f"fold {k}: chose λ {lam} κ {kappa}; held out structured labelled {t[0]}/{t[1]}, "
              f"stochastic served {t[2]}/{t[3]}")
    lam, kappa = pick(pts, kappas)
    print(f"held-out folds pooled: structured labelled {pooled[0]}/{pooled[1]}, stochastic served "
          f"{pooled[2]}/{pooled[3]}; the whole set's choice λ {lam} κ {kappa}")


if __name__ == "__main__":
    main()
