#!/usr/bin/env python3
"""The family classifier's margin beyond the noise model's render (retrieve::NOISE_NULL_MARGIN),
cross-validated on the development set, offline.

Where the product put the noise model first (and the photo has no dark network), the classifier's
nearest family comes first instead when its margin on the photo (squared distance to the noise
class minus that to the nearest family) exceeds the same margin on the noise model's render of
the photo by more than tau. Inputs: a run made without the rule (`proctex fidelity --set
../shared/photos/dev --json`: each patch's choice and whether a chosen family's fidelity is no
worse than the noise model's) and the margins of `examples/null_gate_lab.rs` (its first render's
seed is the ranking's).

Protocol: 4 folds by photo (devset::fold_of); for each held-out fold the tau with the most
structured patches labelled on the other folds among those keeping >= 95 % of their stochastic
patches served (ties: more served, then the middle of the tied taus), scored on the held-out
fold. A stochastic patch the rule changes counts as not served (conservatively). Also printed,
the same way: the photo's margin alone (no render), and the best fitted family first instead of
the classifier's nearest.

Usage: tools/devset_null_gate_cv.py RUN.jsonl NULL.tsv
"""
import json
import sys

from devset_occam_cv import fold_of, patch_overall

QUADRANTS = ["top-left", "top-right", "bottom-left", "bottom-right"]
SKEWNESS = 7  # cues::CUE_NAMES index of "skewness"
DARK_NETWORK_SKEWNESS = -0.599
FOLDS = 4
GRID = [x / 4 for x in range(0, 121)]  # 0 .. 30


def margins(path):
    """(file, quadrant) -> {class: (photo distance, [render distances])}."""
    out = {}
    for line in open(path):
        f = line.rstrip("\n").split("\t")
        d = {}
        for x in f[4:]:
            k, photo, renders = x.split(":")
            d[k] = (float(photo), [float(v) for v in renders.split("/")])
        out[(f[0], int(f[1]))] = d
    return out


def patches(run, null):
    out = []
    for line in open(run):
        if not line.startswith('{"photo"'):
            continue
        p = json.loads(line)["photo"]
        e = p["entry"]
        for i, c in enumerate(p["choices"]):
            d = null[(e["file"], QUADRANTS.index(c["patch"]))]
            nearest = min((k for k in d if k != "noise"), key=lambda k: d[k][0])
            photo = d["noise"][0] - d[nearest][0]
            render = d["noise"][1][0] - d[nearest][1][0]
            served = c["chosen"] == "noise" or (
                patch_overall(p["auto"], i) <= patch_overall(p["noise"], i))
            best = next(r["name"] for r in c["ranking"] if r["name"] != "noise")
            out.append(dict(file=e["file"], structured=e["category"] == "structured",
                            labels=e["families"] or [], chosen=c["chosen"], served=served,
                            nearest=nearest, best=best, beyond=photo - render, photo=photo,
                            dark=c["photo_cues"][SKEWNESS] < DARK_NETWORK_SKEWNESS))
    return out


def tally(pts, key, tau, first):
    labelled = served = 0
    for pt in pts:
        if pt["chosen"] == "noise" and not pt["dark"] and pt[key] > tau:
            chosen, ok = pt[first], False
        else:
            chosen, ok = pt["chosen"], pt["served"]
        if pt["structured"]:
            labelled += chosen in pt["labels"]
        else:
            served += ok
    return labelled, served


def choose(pts, key, first):
    stochastic = sum(not pt["structured"] for pt in pts)
    res = [(tau,) + tally(pts, key, tau, first) for tau in GRID]
    ok = [r for r in res if r[2] >= 0.95 * stochastic]
    top = max((r[1], r[2]) for r in ok)
    tied = [r[0] for r in ok if (r[1], r[2]) == top]
    return tied[len(tied) // 2]


def main():
    pts = patches(sys.argv[1], margins(sys.argv[2]))
    print("the run: labelled %d, served %d" % tally(pts, "beyond", float("inf"), "nearest"))
    for key, first, what in [("beyond", "nearest", "the photo's margin beyond the render's"),
                             ("photo", "nearest", "the photo's margin alone"),
                             ("beyond", "best", "beyond the render's, the best fitted family")]:
        held = [0, 0]
        taus = []
        for f in range(FOLDS):
            train = [pt for pt in pts if fold_of(pt["file"], FOLDS) != f]
            test = [pt for pt in pts if fold_of(pt["file"], FOLDS) == f]
            tau = choose(train, key, first)
            taus.append(tau)
            labelled, served = tally(test, key, tau, first)
            held[0] += labelled
            held[1] += served
        tau = choose(pts, key, first)
        print(f"{what}: held out labelled {held[0]}, served {held[1]} (taus {taus}); "
              f"whole set tau {tau}: labelled %d, served %d" % tally(pts, key, tau, first))


if __name__ == "__main__":
    main()
