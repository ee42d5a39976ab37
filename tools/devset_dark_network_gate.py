#!/usr/bin/env python3
"""The dark-network rule (retrieve::DARK_NETWORK_SKEWNESS) gated, offline: what it does on a
run, and whether the classifier's render-null margin separates the photos it should act on.

The rule puts the fitted families before the noise model on a photo whose detrended luminance is
skewed dark (the `skewness` cue below -0.599), whatever their texture distances. It decides a
patch only where the noise model's texture score would have put it first ("gated" below). This
script replays such a patch with the rule asking, in addition, that the classifier's margin for
its nearest family over the noise class on the photo exceed that margin on the noise model's
render by more than t (the render-null margin of retrieve::RENDER_NULL_MARGIN, computed from the
run's `classifier_distances` and `noise_render_margin`); where it does not, the noise model comes
first (served; not labelled).

Protocol: 4 folds by photo (devset::fold_of); for each held-out fold the t with the most
structured patches labelled on the other folds among those keeping >= 95 % of their stochastic
patches served (ties: the middle of the tied thresholds), scored on the held-out fold; each
fold's t then replayed on the OTHER runs (sets the threshold is not chosen on).

Usage: tools/devset_dark_network_gate.py DEV_RUN.jsonl [OTHER_RUN.jsonl ...]
"""
import math
import sys

from devset_occam_cv import fold_of, noise_and_best, patch_overall, quadrants

DARK_NETWORK_SKEWNESS = -0.599
SKEWNESS = 7
FOLDS = 4


def rows_of(run):
    rows = []
    for p, i, c in quadrants(run):
        noise, best = noise_and_best(c)
        distances = dict(zip(c["classifier"], c["classifier_distances"]))
        nearest = next(k for k in c["classifier"] if k != "noise")
        photo_margin = distances["noise"] - distances[nearest]
        rows.append(dict(
            file=p["entry"]["file"], labels=p["entry"]["families"], chosen=c["chosen"],
            gated=c["photo_cues"][SKEWNESS] < DARK_NETWORK_SKEWNESS
            and noise["score"] <= best["score"],
            unexplained=photo_margin - c["noise_render_margin"],
            served=c["chosen"] == "noise"
            or patch_overall(p["auto"], i) <= patch_overall(p["noise"], i)))
    return rows


def tally(rows, t):
    labelled = served = 0
    for r in rows:
        chosen = r["chosen"] if not r["gated"] or r["unexplained"] > t else "noise"
        if r["labels"] == ["noise"]:
            served += chosen == "noise" or r["served"]
        else:
            labelled += chosen in r["labels"]
    return labelled, served


def choose(rows, grid):
    stochastic = sum(r["labels"] == ["noise"] for r in rows)
    scored = [(tally(rows, t), t) for t in grid]
    ok = [(s, t) for s, t in scored if s[1] >= 0.95 * stochastic]
    best = max(s for s, _ in ok)
    tied = [t for s, t in ok if s == best]
    return tied[len(tied) // 2]


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    dev = rows_of(sys.argv[1])
    others = [(run, rows_of(run)) for run in sys.argv[2:]]
    grid = [-math.inf] + [k / 4 for k in range(-80, 81)] + [math.inf]
    for name, rows in [(sys.argv[1], dev)] + others:
        gated = [r for r in rows if r["gated"]]
        structured = [r for r in gated if r["labels"] != ["noise"]]
        print(f"{name}: {len(gated)} patches the rule decides ({len(structured)} structured, "
              f"{sum(r['chosen'] in r['labels'] for r in structured)} of them labelled); "
              "labelled, served with the rule: %d, %d; without it: %d, %d"
              % (tally(rows, -math.inf) + tally(rows, math.inf)))
        print("  their render-null margins (S structured, s stochastic): " + " ".join(
            f"{r['unexplained']:.1f}{'S' if r['labels'] != ['noise'] else 's'}"
            for r in sorted(gated, key=lambda r: r["unexplained"])))
    held, chosen = [0, 0], []
    for f in range(FOLDS):
        t = choose([r for r in dev if fold_of(r["file"], FOLDS) != f], grid)
        chosen.append(t)
        a, b = tally([r for r in dev if fold_of(r["file"], FOLDS) == f], t)
        held = [held[0] + a, held[1] + b]
    print(f"held out (t chosen {', '.join(f'{t:.2f}' for t in chosen)}): labelled {held[0]}, "
          f"served {held[1]}")
    for name, rows in others:
        print(f"{name} at the folds' t: " + ", ".join("%d / %d" % tally(rows, t) for t in chosen))


if __name__ == "__main__":
    main()
