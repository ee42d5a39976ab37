#!/usr/bin/env python3
"""The family classifier's margin beyond the first candidate's render (retrieve::RENDER_NULL_MARGIN),
cross-validated on the development set, offline.

The first candidate by the scores is the noise model where it would come first by its score
(below every fitted family's, and the photo has no dark network), else the fitted family with the
best score. The classifier's nearest family comes first instead when its margin over the first
candidate's class on the photo (the squared distance to that class minus that to the nearest
family) exceeds the same margin on the first candidate's own render by more than tau, and, where
the first candidate is a family, the photo's own margin exceeds tau as well. Everything
is in a run's JSON (`proctex fidelity --set ../shared/photos/dev --json`): the ranking's scores,
the classifier's distances of the patch (`classifier`, `classifier_distances`), of the noise
model's render (`noise_render_margin`) and of every candidate's render (the ranking's
`classifier_distances`, recorded since the rule covers families), whether a chosen family's
fidelity is no worse than the noise model's; so the run may be made with or without the rule.
Runs made before the yardstick recorded `noise_render_margin` take the margins from
`examples/null_gate_lab.rs`'s TSV instead (its first render's seed is the ranking's); runs made
before it recorded the candidates' classes measure the rule for the noise model alone.

Protocol: 4 folds by photo (devset::fold_of); for each held-out fold the tau with the most
structured patches labelled on the other folds among those keeping >= 95 % of their stochastic
patches served (ties: more served, then the middle of the tied taus), scored on the held-out
fold. A stochastic patch served by a family that the run did not choose counts as not served
(conservatively). Also printed, the same way: the photo's margin alone (no render), and the best
fitted family first instead of the classifier's nearest; and, as a check, how many of the run's
choices the replay at `--current` (the run's own threshold; inf for a run without the rule)
reproduces.

Usage: tools/devset_null_gate_cv.py RUN.jsonl [NULL.tsv] [--current TAU] [--current-family TAU]
(--current: the run's own threshold, for both rules where the run recorded the candidates'
classes; --current-family: the run's threshold for the best family where it differs, inf for a
run made with the rule for the noise model alone)
"""
import json
import sys

from devset_occam_cv import fold_of, patch_overall

QUADRANTS = ["top-left", "top-right", "bottom-left", "bottom-right"]
SKEWNESS = 7  # cues::CUE_NAMES index of "skewness"
DARK_NETWORK_SKEWNESS = -0.599
FITTED = 3  # retrieve::RENDER_ORDERED
FOLDS = 4
GRID = [x / 4 for x in range(0, 121)]  # 0 .. 30


def lab_margins(path):
    """(file, quadrant) -> the noise render's margin for the photo's nearest family, from the
    laboratory's TSV (its first render)."""
    out = {}
    for line in open(path):
        f = line.rstrip("\n").split("\t")
        d = {}
        for x in f[4:]:
            k, photo, renders = x.split(":")
            d[k] = (float(photo), float(renders.split("/")[0]))
        nearest = min((k for k in d if k != "noise"), key=lambda k: d[k][0])
        out[(f[0], int(f[1]))] = d["noise"][1] - d[nearest][1]
    return out


def patches(run, lab):
    out = []
    for line in open(run):
        if not line.startswith('{"photo"'):
            continue
        p = json.loads(line)["photo"]
        e = p["entry"]
        for i, c in enumerate(p["choices"]):
            classes = dict(zip(c["classifier"], c["classifier_distances"]))
            families = [k for k in c["classifier"] if k != "noise"]
            nearest = families[0]
            photo = classes["noise"] - classes[nearest]
            if lab is not None:
                render = lab[(e["file"], QUADRANTS.index(c["patch"]))]
            else:
                render = c["noise_render_margin"]
            score = {r["name"]: r["score"] for r in c["ranking"]}
            fitted = [k for k in families[:FITTED] if k in score]
            best = min(fitted, key=lambda k: score[k])
            dark = c["photo_cues"][SKEWNESS] < DARK_NETWORK_SKEWNESS
            by_score = not dark and score["noise"] <= score[best]
            no_worse = patch_overall(p["auto"], i) <= patch_overall(p["noise"], i)
            # The best family's margin beyond its own render's, at most the photo's own (None
            # where the run did not record the candidates' classes, or the best family is the
            # nearest).
            rendered = {r["name"]: r.get("classifier_distances") for r in c["ranking"]}
            family = None
            if best != nearest and rendered.get(best):
                r = rendered[best]
                own = classes[best] - classes[nearest]
                # For a family, no more than the photo's own margin (retrieve::RENDER_NULL_MARGIN).
                family = min(own - (r[best] - r[nearest]), own)
            out.append(dict(file=e["file"], structured=e["category"] == "structured",
                            labels=e["families"] or [], chosen=c["chosen"], no_worse=no_worse,
                            by_score=by_score, nearest=nearest, best=best,
                            beyond=photo - render, photo=photo, family=family))
    return out


def choice(pt, key, tau, first, tau_family=float("inf")):
    """The first model with the rule at `tau` for the noise model and `tau_family` for the best
    family (`first`: which family the rule puts first where the noise model would be first)."""
    if pt["by_score"]:
        return pt[first] if pt[key] > tau else "noise"
    if pt["family"] is not None and pt["family"] > tau_family:
        return pt["nearest"]
    if pt["chosen"] == pt["nearest"] and pt["family"] is not None:
        return pt["best"]  # the run's rule put the nearest first; without it, the best
    return pt["chosen"]


def tally(pts, key, tau, first, tau_family=float("inf")):
    labelled = served = 0
    for pt in pts:
        chosen = choice(pt, key, tau, first, tau_family)
        if pt["structured"]:
            labelled += chosen in pt["labels"]
        else:
            served += chosen == "noise" or (chosen == pt["chosen"] and pt["no_worse"])
    return labelled, served


def choose(pts, key, first, both=False):
    stochastic = sum(not pt["structured"] for pt in pts)
    res = [(tau,) + tally(pts, key, tau, first, tau if both else float("inf")) for tau in GRID]
    ok = [r for r in res if r[2] >= 0.95 * stochastic]
    top = max((r[1], r[2]) for r in ok)
    tied = [r[0] for r in ok if (r[1], r[2]) == top]
    return tied[len(tied) // 2]


def main():
    args = sys.argv[1:]
    current = float("inf")
    if "--current" in args:
        k = args.index("--current")
        current = float(args[k + 1])
        del args[k:k + 2]
    current_family = current
    if "--current-family" in args:
        k = args.index("--current-family")
        current_family = float(args[k + 1])
        del args[k:k + 2]
    lab = lab_margins(args[1]) if len(args) > 1 else None
    pts = patches(args[0], lab)
    families = any(pt["family"] is not None for pt in pts)
    tau_family = current_family if families else float("inf")
    same = sum(choice(pt, "beyond", current, "nearest", tau_family) == pt["chosen"] for pt in pts)
    print(f"replay at tau {current}: {same} of {len(pts)} of the run's choices; "
          "without the rule: labelled %d, served %d" % tally(pts, "beyond", float("inf"), "nearest"))
    variants = [("the photo's margin beyond the noise model's render", "beyond", "nearest", False),
                ("the photo's margin alone", "photo", "nearest", False),
                ("beyond the noise model's render, the best fitted family", "beyond", "best", False)]
    if families:
        variants.insert(0, ("beyond the first candidate's render (the noise model's or the best "
                            "family's)", "beyond", "nearest", True))
    for what, key, first, both in variants:
        held = [0, 0]
        taus = []
        for f in range(FOLDS):
            train = [pt for pt in pts if fold_of(pt["file"], FOLDS) != f]
            test = [pt for pt in pts if fold_of(pt["file"], FOLDS) == f]
            tau = choose(train, key, first, both)
            taus.append(tau)
            labelled, served = tally(test, key, tau, first, tau if both else float("inf"))
            held[0] += labelled
            held[1] += served
        tau = choose(pts, key, first, both)
        whole = tally(pts, key, tau, first, tau if both else float("inf"))
        print(f"{what}: held out labelled {held[0]}, served {held[1]} (taus {taus}); "
              f"whole set tau {tau}: labelled %d, served %d" % whole)


if __name__ == "__main__":
    main()
