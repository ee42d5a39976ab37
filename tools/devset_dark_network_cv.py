#!/usr/bin/env python3
"""Cross-validates the dark-network threshold of the ranking on the development set, offline.

Input: the JSON lines of `proctex fidelity --set ../shared/photos/dev --json`, whose patches
carry their whole ranking and the source patch's structure cues (`photo_cues`, in the order of
`proctex::cues::CUE_NAMES`). The ranking (retrieve::Suggester::suggestions) puts the noise model
first when its texture distance is below the best family's plus the OCCAM margin, except on a
patch whose cue (default: the skewness of its detrended luminance) is below the threshold: there
the best family comes first whatever the noise model's distance. So the choice under another
threshold needs no new analysis.

Protocol: F folds by devset::fold_of (FNV-1a of the file name); for each held-out fold the
threshold is chosen on the other folds: the largest structured labelled rate among the
thresholds that keep ≥ 95 % of the stochastic patches served (the run's measure: the noise
model, or the run's own family choice where its fidelity was no worse; a stochastic patch the
threshold moves to a family the run did not choose has no measured fidelity and counts as not
served); ties go to the lowest threshold (the fewest patches moved). "off" (no threshold) is
one of the candidates. The held-out folds' numbers are pooled.

With --nested the cue and its direction (below or above the threshold) are chosen on the
training folds too, among all ten cues: the cross-validated value of choosing a cue this way,
free of the selection that picked the skewness.

Usage: tools/devset_dark_network_cv.py RUN.jsonl [--folds F] [--cue skewness] [--current T]
       [--nested]
"""
import json
import sys

from devset_occam_cv import choose as occam_choose
from devset_occam_cv import fold_of
from devset_occam_cv import patches as occam_patches

CUE_NAMES = ["lattice", "lattice2", "lobe_elongation", "coherence", "axis_alignment",
             "kurtosis", "kurtosis_fine", "skewness", "bimodality", "edge_sparsity"]
OFF = float("-inf")
OCCAM = 0.2  # retrieve::NOISE_MODEL_MARGIN (called OCCAM until 2026-11-27)


def patches(photos, cue):
    """The OCCAM script's patches (at the shipped OCCAM), each with its cues."""
    out = []
    pts = iter(occam_patches(photos, OCCAM))
    for p in photos:
        for c in p["choices"]:
            pt = next(pts)
            out.append(dict(pt, cue=c["photo_cues"][CUE_NAMES.index(cue)], cues=c["photo_cues"],
                            noise_first=occam_choose(pt, OCCAM) == "noise"))
    return out


def choose(pt, threshold):
    if pt["cue"] < threshold:
        return pt["best"]
    return "noise" if pt["noise_first"] else pt["best"]


def tally(pts, chooser):
    """(structured labelled, structured, stochastic served, stochastic) when `chooser(pt)` names
    each patch's model."""
    s = [pt for pt in pts if pt["category"] == "structured"]
    t = [pt for pt in pts if pt["category"] == "stochastic"]
    lab = sum(chooser(pt) in pt["labels"] for pt in s)
    served = sum(1 for pt in t if (c := chooser(pt)) == "noise"
                 or (c == pt["chosen"] and pt["family_ok"]))
    return lab, len(s), served, len(t)


def counts(pts, threshold):
    return tally(pts, lambda pt: choose(pt, threshold))


def pick(pts):
    # Candidates: off, and the midpoints between consecutive cue values (a threshold moves
    # the patches below it; between two patches is the only place where that set changes).
    values = sorted({pt["cue"] for pt in pts})
    grid = [OFF] + [(a + b) / 2 for a, b in zip(values, values[1:])]
    best = None
    for th in grid:
        lab, ns, served, nt = counts(pts, th)
        if served >= 0.95 * nt and (best is None or lab > best[1]):
            best = (th, lab)
    return best[0] if best else OFF


def nested_pick(pts):
    """(cue index, sign, threshold) of the best rule over every cue and direction on `pts`:
    the rule moves a patch when sign × cue < sign × threshold."""
    best = None
    for i in range(len(CUE_NAMES)):
        for sign in (1, -1):
            view = [dict(pt, cue=sign * pt["cues"][i]) for pt in pts]
            th = pick(view)
            lab = counts(view, th)[0]
            if best is None or lab > best[0]:
                best = (lab, i, sign, th)
    return best[1:]


def held_out(pts, folds, choose_rule):
    """Every fold held out once: `choose_rule(train)` gives (cue index, sign, threshold), whose
    counts on the held-out fold are printed and pooled."""
    pooled = [0, 0, 0, 0]
    for k in range(folds):
        train = [pt for pt in pts if fold_of(pt["file"], folds) != k]
        test = [pt for pt in pts if fold_of(pt["file"], folds) == k]
        if not test:
            continue
        i, sign, th = choose_rule(train)
        c = counts([dict(pt, cue=sign * pt["cues"][i]) for pt in test], th)
        pooled = [a + b for a, b in zip(pooled, c)]
        side = "below" if sign == 1 else "above"
        print(f"fold {k}: chosen on the others: {CUE_NAMES[i]} {side} {fmt(sign * th)}; held "
              f"out: structured labelled {c[0]}/{c[1]}, stochastic served {c[2]}/{c[3]}")
    lab, ns, served, nt = pooled
    print(f"held-out folds pooled: structured labelled {lab}/{ns} = {lab / max(ns, 1):.1%}, "
          f"stochastic served {served}/{nt} = {served / max(nt, 1):.1%}")


def fmt(th):
    return "off" if th == OFF else f"{th:.3f}"


def main():
    args = sys.argv[1:]
    folds, cue, current = 4, "skewness", OFF
    if "--folds" in args:
        folds = int(args[args.index("--folds") + 1])
    if "--cue" in args:
        cue = args[args.index("--cue") + 1]
    if "--current" in args:
        current = float(args[args.index("--current") + 1])
    photos = [json.loads(l)["photo"] for l in open(args[0]) if '"photo"' in l]
    pts = patches(photos, cue)
    agree = sum(choose(pt, current) == pt["chosen"] for pt in pts)
    print(f"{len(photos)} photos, {len(pts)} patches; the numbers reproduce {agree}/{len(pts)} "
          f"choices at threshold {fmt(current)} on {cue}")
    lab, ns, served, nt = counts(pts, current)
    print(f"as run: structured labelled {lab}/{ns}, stochastic served {served}/{nt}")
    if "--nested" in args:
        held_out(pts, folds, nested_pick)
        return
    i = CUE_NAMES.index(cue)
    held_out(pts, folds, lambda train: (i, 1, pick(train)))
    th = pick(pts)
    lab, ns, served, nt = counts(pts, th)
    print(f"whole set (the value to ship): threshold {fmt(th)}; structured labelled {lab}/{ns}, "
          f"stochastic served {served}/{nt}")


if __name__ == "__main__":
    main()
