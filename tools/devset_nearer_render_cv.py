#!/usr/bin/env python3
"""The nearer render in scattering space (retrieve::NEARER_RENDER_MARGIN), cross-validated on the
development set, offline.

Where the ranking puts the noise model first, the classifier's nearest family comes first
instead when the patch is nearer to that family's fitted render than to the noise model's in the
scattering space by more than t (`nearer_render_margin` in the run's JSON, recorded wherever the
ranking's other rules put the noise model first: `proctex fidelity --set ../shared/photos/dev
--json`), so the run may be made with the rule or without it.

Protocol: 4 folds by photo (devset::fold_of); for each held-out fold the t with the most
structured patches labelled on the other folds among those keeping >= 95 % of their stochastic
patches served (ties: more served, then the middle of the tied thresholds), scored on the
held-out fold. A stochastic patch switched to a family counts as not served (conservatively: the
run did not measure that family's fidelity). The whole set's choice the same way. With `--check
TAU WITH.jsonl`, also how many of WITH's choices (a run made with the rule at TAU) the replay of
RUN at TAU reproduces. With `--margins TSV COLUMN`, the margins are read from column COLUMN
(0-based) of a TSV whose first two columns are the photo and the patch
(`examples/nearer_render_lab.rs`: 4 the fast fit's, 5 the final fit's) instead of the run's.

With `--ratio`, the rule's statistic is the log ratio of the two distances whose difference the
margin is, ln(|S(photo) − S(noise render)| / |S(photo) − S(family render)|) (scale-free: a photo
far from both renders needs a proportionally larger gap), from the run's
`nearer_render_distances`.

Usage: tools/devset_nearer_render_cv.py RUN.jsonl [--check TAU WITH.jsonl | --margins TSV COLUMN |
--ratio] [--at TAU]

With `--at TAU`, only the replay at TAU against the run without the rule (a set the threshold is
not chosen on: the shipped samples, textures never tuned on), with what it switches.
"""
import math
import sys

from devset_occam_cv import fold_of, patch_overall, quadrants

FOLDS = 4


def rows_of(run, margins=None, ratio=False):
    """(photo, labels, choice) for every patch of the run, the choice with `before` (the model
    the ranking put first before the rule: the noise model wherever the run recorded a margin,
    since the ranking measures it only there), `served` (that model is the noise model, or a
    family no farther than it), `nearest` (the classifier's nearest family) and `margin` (the
    run's, or `margins`' {(photo, patch): margin} for a run made without the rule)."""
    rows = []
    for p, i, c in quadrants(run):
        recorded = c.get("nearer_render_margin")
        before = "noise" if recorded is not None else c["chosen"]
        if margins is not None:
            margin = margins[(p["entry"]["file"], c["patch"])]
        elif ratio:
            d = c.get("nearer_render_distances")
            margin = -math.inf if d is None else math.log(d[0] / max(d[1], 1e-12))
        else:
            margin = -math.inf if recorded is None else recorded
        served = before == "noise" or (
            patch_overall(p["auto"], i) <= patch_overall(p["noise"], i))
        nearest = next((k for k in c["classifier"] if k != "noise"), None)
        rows.append((p["entry"]["file"], p["entry"]["families"],
                     dict(c, before=before, served=served, nearest=nearest, margin=margin)))
    return rows


def chosen_at(c, t):
    if c["before"] == "noise" and c["nearest"] and c["margin"] > t:
        return c["nearest"]
    return c["before"]


def tally(rows, t):
    """Structured patches labelled and stochastic patches served with the rule at t."""
    labelled = served = 0
    for _, labels, c in rows:
        chosen = chosen_at(c, t)
        if labels == ["noise"]:
            served += chosen == c["before"] and c["served"]
        else:
            labelled += chosen in labels
    return labelled, served


def choose(rows, grid):
    """The t with the most structured patches labelled among those keeping >= 95 % of the
    stochastic patches served; ties: more served, then the middle of the tied thresholds."""
    stochastic = sum(labels == ["noise"] for _, labels, _ in rows)
    scored = [(tally(rows, t), t) for t in grid]
    ok = [(s, t) for s, t in scored if s[1] >= 0.95 * stochastic]
    best = max(s for s, _ in ok)
    tied = [t for s, t in ok if s == best]
    finite = [t for t in tied if math.isfinite(t)]
    if not finite:
        return math.inf
    return finite[len(finite) // 2] if len(finite) % 2 else (
        finite[len(finite) // 2 - 1] + finite[len(finite) // 2]) / 2


def thresholds(rows):
    """Between each two of the recorded margins of noise choices, and infinity."""
    at = sorted({c["margin"] for _, _, c in rows
                 if c["before"] == "noise" and math.isfinite(c["margin"])})
    return [(a + b) / 2 for a, b in zip(at, at[1:])] + [math.inf]


def main():
    args = sys.argv[1:]
    if not args or args[0].startswith("-"):
        sys.exit(__doc__)
    margins = None
    if len(args) == 4 and args[1] == "--margins":
        column = int(args[3])
        margins = {}
        for line in open(args[2]):
            t = line.rstrip("\n").split("\t")
            margins[(t[0], t[1])] = float(t[column])
    rows = rows_of(args[0], margins, ratio="--ratio" in args)
    if "--at" in args:
        tau = float(args[args.index("--at") + 1])
        structured = sum(labels != ["noise"] for _, labels, _ in rows)
        print(f"{structured} structured and {len(rows) - structured} stochastic patches")
        print("without the rule: labelled %d, served %d" % tally(rows, math.inf))
        print("at %.4f: labelled %d, served %d" % ((tau,) + tally(rows, tau)))
        for p, labels, c in rows:
            if chosen_at(c, tau) != c["before"]:
                mark = "noise" if labels == ["noise"] else (
                    "labelled" if c["nearest"] in labels else "wrong")
                print(f"  switched: {p} {c['patch']} -> {c['nearest']} ({mark}; {c['margin']:.3f})")
        return
    grid = thresholds(rows)
    structured = sum(labels != ["noise"] for _, labels, _ in rows)
    stochastic = len(rows) - structured
    print(f"{structured} structured and {stochastic} stochastic patches")
    print("without the rule: labelled %d, served %d" % tally(rows, math.inf))
    held, chosen, switched = [0, 0], [], []
    for f in range(FOLDS):
        train = [r for r in rows if fold_of(r[0], FOLDS) != f]
        test = [r for r in rows if fold_of(r[0], FOLDS) == f]
        t = choose(train, grid)
        chosen.append(t)
        a, b = tally(test, t)
        held = [held[0] + a, held[1] + b]
        switched += [(p, c["patch"], c["nearest"], labels) for p, labels, c in test
                     if chosen_at(c, t) != c["before"]]
    base = tally(rows, math.inf)
    se = lambda k, n: math.sqrt(k * (n - k) / n) if n else 0.0
    print(f"held out (4 folds by photo; t chosen {', '.join('%.3f' % t for t in chosen)}): "
          f"structured labelled {base[0]} -> {held[0]} of {structured} (± {se(held[0], structured):.1f}), "
          f"stochastic served {base[1]} -> {held[1]} of {stochastic}")
    for p, patch, family, labels in switched:
        mark = "noise" if labels == ["noise"] else ("labelled" if family in labels else "wrong")
        print(f"  switched held out: {p} {patch} -> {family} ({mark})")
    t = choose(rows, grid)
    print("the whole set's choice: t %.4f, labelled %d, served %d" % ((t,) + tally(rows, t)))
    if len(args) == 4 and args[1] == "--check":
        tau, other = float(args[2]), rows_of(args[3])
        same = sum(chosen_at(c, tau) == o["chosen"] for (_, _, c), (_, _, o) in zip(rows, other))
        print(f"replay at {tau} against {args[3]}: {same} of {len(rows)} choices the same")


if __name__ == "__main__":
    main()
