#!/usr/bin/env python3
"""Cross-validates an additive prior on the families' structure distances, offline.

Input: the JSON lines of `proctex fidelity --set ../shared/photos/dev --json`, whose patches
carry their whole ranking. The ranking is a function of those numbers
(retrieve::Suggester::suggestions): the families are ordered by structure distance (refined,
else retrieved); the noise model comes first when its texture distance is below the best
family's plus OCCAM × the patch's self-distance, unless the photo's detrended luminance is
skewed dark (cue `skewness` below retrieve::DARK_NETWORK_SKEWNESS), when the best family comes
first. A prior adds a bias to chosen families' structure distances before they are ordered.

Protocol: F folds by devset::fold_of; on the other folds the biases are chosen (coordinate
search over a grid, the most structured labelled patches among the values that serve ≥ 90 % of
the stochastic patches) and the held-out fold is scored. A stochastic patch is served when it
keeps the noise model, or when the run chose the same family and measured it no farther from
the photo than the noise model (a family the run did not choose has no measured fidelity: not
served, conservatively).

Usage: tools/devset_family_prior_cv.py RUN.jsonl
"""
import json
import sys

from devset_dark_network_cv import CUE_NAMES, OCCAM, tally
from devset_occam_cv import fold_of
from devset_occam_cv import patches as occam_patches

DARK_NETWORK_SKEWNESS = -0.599  # retrieve::DARK_NETWORK_SKEWNESS
GRID = [round(0.1 * i, 1) for i in range(-15, 6)]
LATTICES = ["brick", "grid", "cells", "planks"]


def patches(photos):
    """The OCCAM script's patches, each with its dark-network flag and every family's
    (structure distance, texture distance)."""
    out = []
    pts = iter(occam_patches(photos, OCCAM))
    for p in photos:
        for c in p["choices"]:
            pt = next(pts)
            fams = [r for r in c["ranking"] if r["name"] != "noise"]
            out.append(dict(
                pt, dark=c["photo_cues"][CUE_NAMES.index("skewness")] < DARK_NETWORK_SKEWNESS,
                families={r["name"]: (r["refined"] if r["refined"] is not None
                                      else r["retrieval"], r["distance"]) for r in fams}))
    return out


def choose(pt, bias):
    best = min(pt["families"], key=lambda n: pt["families"][n][0] + bias.get(n, 0.0))
    if pt["dark"]:
        return best
    return "noise" if pt["noise_d"] < pt["families"][best][1] + OCCAM * pt["self_d"] else best


def rates(pts, bias):
    return tally(pts, lambda pt: choose(pt, bias))


def objective(pts, bias):
    labelled, _, served, stochastic = rates(pts, bias)
    return (served >= 0.9 * stochastic, labelled, served)


def fit(pts, groups, names):
    bias = {n: 0.0 for n in names}
    current = objective(pts, bias)
    for _ in range(3):
        for group in groups:
            best = (current, 0.0, bias[group[0]])
            for v in GRID:
                trial = dict(bias, **{n: v for n in group})
                o = objective(pts, trial)
                if (o, -abs(v)) > best[:2]:
                    best = (o, -abs(v), v)
            bias.update({n: best[2] for n in group})
            current = best[0]
    return bias


def main():
    photos = [json.loads(l)["photo"] for l in open(sys.argv[1]) if '"photo"' in l]
    pts = patches(photos)
    agree = sum(choose(pt, {}) == pt["chosen"] for pt in pts)
    print(f"{len(pts)} patches; the numbers reproduce {agree}/{len(pts)} choices")
    names = sorted(pts[0]["families"])
    print("no prior: structured labelled {}/{}, stochastic served {}/{}".format(*rates(pts, {})))
    for label, groups in [("one per family", [[n] for n in names]),
                          ("one for the lattices", [LATTICES])]:
        bias = fit(pts, groups, names)
        chosen = {k: v for k, v in bias.items() if v}
        print(f"{label}, fitted on the whole set (for reading): "
              "labelled {}/{}, served {}/{}".format(*rates(pts, bias)), chosen)
        for folds in (4, 5):
            labelled = served = 0
            for k in range(folds):
                train = [pt for pt in pts if fold_of(pt["file"], folds) != k]
                test = [pt for pt in pts if fold_of(pt["file"], folds) == k]
                lab, _, srv, _ = rates(test, fit(train, groups, names))
                labelled += lab
                served += srv
            print(f"  {folds} folds, held out pooled: structured labelled {labelled}, "
                  f"stochastic served {served}")


if __name__ == "__main__":
    main()
