#!/usr/bin/env python3
"""Cross-validates ordering the families by their fitted renders' texture distance, offline.

Input: the JSON lines of `proctex fidelity --set ../shared/photos/dev --json`, whose patches
carry their whole ranking (every family's structure distance, retrieval and refined, and the
texture distance of its fitted render), the noise model's texture distance and the source
patch's cues. The ranking (retrieve::Suggester::suggestions) orders the families by structure
distance; the noise model comes first when its texture distance is below the best family's
plus the margin, except on a dark network (skewness below retrieve::DARK_NETWORK_SKEWNESS),
where the best family comes first. Here the families among the first K by structure distance
are ordered instead by (1 − w) · structure + w · texture distance (w = 0: the product), the
noise model placed against the new best as the product places it. Every choice is a function of
the recorded numbers (the script first checks that w = 0 reproduces the run's choices).

Protocol: 4 folds by devset::fold_of; on each held-out fold, w is chosen on the other three (the
most structured patches labelled among the values that keep ≥ 95 % of the stochastic patches
served, as the dark-network threshold is chosen; ties to the smaller w). A stochastic patch is
served when the choice is the noise model, or the family the run chose and measured no farther
than the noise model (a family the run did not choose has no measured fidelity: not served).

Usage: tools/devset_family_order_cv.py RUN.jsonl [--k K] [--grid 0,1]
"""
import json
import sys

from devset_occam_cv import fold_of
from devset_occam_cv import patches as occam_patches

OCCAM = 0.2  # retrieve::NOISE_MODEL_MARGIN
DARK_NETWORK_SKEWNESS = -0.599  # retrieve::DARK_NETWORK_SKEWNESS
SKEWNESS = 7  # index of the skewness in proctex::cues::CUE_NAMES
RENDER_ORDERED, TEXTURE_WEIGHT = 3, 0.9  # retrieve::RENDER_ORDERED, retrieve::TEXTURE_WEIGHT
FOLDS = 4


def structure(r):
    return r["refined"] if r["refined"] is not None else r["retrieval"]


def patches(photos):
    """The OCCAM script's patches, each with its families nearest first by structure distance
    and its cues' skewness (dark network below the threshold)."""
    cues = [c["photo_cues"] for p in photos for c in p["choices"]]
    return [dict(pt, families=sorted(pt["families"], key=structure), skew=cue[SKEWNESS])
            for pt, cue in zip(occam_patches(photos, OCCAM), cues)]


def choose(pt, w, k, margin=OCCAM, dark=DARK_NETWORK_SKEWNESS):
    """The choice with the first `k` families reordered at weight `w`, the noise model's margin
    `margin` × the self distance and the dark-network threshold `dark`."""
    best = min(pt["families"][:k], key=lambda r: (1 - w) * structure(r) + w * r["distance"])
    if pt["skew"] < dark:
        return best["name"]
    return "noise" if pt["noise_d"] < best["distance"] + margin * pt["self_d"] else best["name"]


def tally(pts, w, k, margin=OCCAM, dark=DARK_NETWORK_SKEWNESS):
    s = [pt for pt in pts if pt["category"] == "structured"]
    t = [pt for pt in pts if pt["category"] == "stochastic"]
    labelled = sum(choose(pt, w, k, margin, dark) in pt["labels"] for pt in s)
    served = sum(1 for pt in t if (c := choose(pt, w, k, margin, dark)) == "noise"
                 or (c == pt["chosen"] and pt["family_ok"]))
    return labelled, len(s), served, len(t)


def cross_validate(pts, candidates, tally_at, prefer, baseline):
    """Each of the FOLDS folds held out in turn: the candidate chosen on the other folds (the
    most structured patches labelled among those that keep ≥ 95 % of the stochastic patches
    served; ties by `prefer(candidate, tally)`), its tally on the held-out fold and the
    `baseline` candidate's. Returns (fold, chosen, held, base) per fold and the pooled held and
    base tallies."""
    folds, pooled, base = [], [0, 0, 0, 0], [0, 0, 0, 0]
    for f in range(FOLDS):
        train = [pt for pt in pts if fold_of(pt["file"], FOLDS) != f]
        test = [pt for pt in pts if fold_of(pt["file"], FOLDS) == f]
        scored = [(c, tally_at(train, c)) for c in candidates]
        ok = [x for x in scored if x[1][2] >= 0.95 * x[1][3]] or scored
        chosen = max(ok, key=lambda x: (x[1][0], prefer(*x)))[0]
        held, b = tally_at(test, chosen), tally_at(test, baseline)
        pooled = [a + h for a, h in zip(pooled, held)]
        base = [a + h for a, h in zip(base, b)]
        folds.append((f, chosen, held, b))
    return folds, pooled, base


def main():
    args = sys.argv[1:]
    k = int(args[args.index("--k") + 1]) if "--k" in args else 9
    grid = ([float(x) for x in args[args.index("--grid") + 1].split(",")] if "--grid" in args
            else [i / 20 for i in range(21)])
    photos = [json.loads(line)["photo"] for line in open(args[0]) if '"photo"' in line]
    pts = patches(photos)
    agree = sum(choose(pt, 0.0, 9) == pt["chosen"] for pt in pts)
    product = sum(choose(pt, TEXTURE_WEIGHT, RENDER_ORDERED) == pt["chosen"] for pt in pts)
    print(f"{len(photos)} photos, {len(pts)} patches; w = 0 (the order by structure distance) "
          f"reproduces {agree}/{len(pts)} choices, the product's order since 2026-11-29 "
          f"(w = {TEXTURE_WEIGHT}, k = {RENDER_ORDERED}) {product}/{len(pts)}")
    print(f"first {k} families by structure distance reordered; whole set (for reading):")
    for w in grid:
        lab, ns, served, nt = tally(pts, w, k)
        print(f"  w {w:4.2f}: structured labelled {lab}/{ns}, stochastic served {served}/{nt}")
    folds, pooled, base = cross_validate(pts, grid, lambda ps, w: tally(ps, w, k),
                                         lambda w, _: -w, 0.0)
    for f, w, held, b in folds:
        print(f"fold {f}: w chosen on the others {w:.2f}; held out structured labelled "
              f"{held[0]}/{held[1]} (w = 0: {b[0]}), stochastic served {held[2]}/{held[3]} "
              f"(w = 0: {b[2]})")
    print(f"held-out folds pooled: structured labelled {pooled[0]}/{pooled[1]} (w = 0: "
          f"{base[0]}), stochastic served {pooled[2]}/{pooled[3]} (w = 0: {base[2]})")


if __name__ == "__main__":
    main()
