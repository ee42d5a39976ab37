#!/usr/bin/env python3
"""The nearer-render rule with the family's complete final fit compared where its first round
falls short, cross-validated over the development set and its blurred copy together, offline.

The product's rule (retrieve::NEARER_RENDER_MARGIN, t = 1.4801) compares the photo's scattering
distances to the noise model's render and to the first round of the classifier's nearest
family's final fit. A laboratory build (`tools/not_kept/nearer_complete.patch`, run with
`PROCTEX_LAB_NEARER=max`) compares, where that first round's margin is at most t, the complete
final fit's render as well and keeps the larger margin.
The complete fit costs its time on every patch where the rule is measured and fails (the
stochastic ones above all), so the variant is bounded below: the complete fit is tried only
where the first round's margin exceeds L. L = +inf is the product, L = -inf the laboratory run.

Input: pairs of runs (`proctex fidelity --set SET --json`), each set's product run and its
laboratory run (`PROCTEX_LAB_NEARER=max`). The first round's margin is the product run's
`nearer_render_margin`; the complete fit's is the laboratory run's where it is larger (where it
is not, the rule keeps the first round's, which is all the replay needs).

Protocol: 4 folds by photo file (devset::fold_of; a photo's copies in every set in the same
fold); for each held-out fold the L with the most structured patches labelled on the other folds
(every set pooled) among those keeping >= 95 % of their stochastic patches served (ties: more
served, then the largest L: the least extra time), scored on the held-out fold. A stochastic
patch switched to a family counts as not served (as in devset_nearer_render_cv.py).

Usage: tools/devset_nearer_complete_cv.py PRODUCT.jsonl LAB.jsonl [PRODUCT2.jsonl LAB2.jsonl ...]
"""
import math
import sys

from devset_nearer_render_cv import rows_of
from devset_occam_cv import fold_of

FOLDS = 4
THRESHOLD = 1.4801


def paired_rows(product, lab):
    """The product run's rows, each with `complete`: the laboratory run's margin where it is
    larger than the product's first-round margin, else -inf."""
    labbed = {(p, c["patch"]): c["margin"] for p, _, c in rows_of(lab)}
    rows = []
    for p, labels, c in rows_of(product):
        other = labbed[(p, c["patch"])]
        complete = other if other > c["margin"] else -math.inf
        rows.append((p, labels, dict(c, complete=complete)))
    return rows


def chosen_at(c, bound):
    if c["before"] != "noise" or not c["nearest"]:
        return c["before"]
    margin = c["margin"]
    if THRESHOLD >= margin > bound:
        margin = max(margin, c["complete"])
    return c["nearest"] if margin > THRESHOLD else c["before"]


def tally(rows, bound):
    labelled = served = tried = 0
    for _, labels, c in rows:
        chosen = chosen_at(c, bound)
        tried += c["before"] == "noise" and THRESHOLD >= c["margin"] > bound
        if labels == ["noise"]:
            served += chosen == c["before"] and c["served"]
        else:
            labelled += chosen in labels
    return labelled, served, tried


def choose(rows, grid):
    stochastic = sum(labels == ["noise"] for _, labels, _ in rows)
    scored = [(tally(rows, b), b) for b in grid]
    ok = [(s, b) for s, b in scored if s[1] >= 0.95 * stochastic]
    best = max((s[0], s[1]) for s, _ in ok)
    return max(b for s, b in ok if (s[0], s[1]) == best)


def main():
    args = sys.argv[1:]
    if len(args) < 2 or len(args) % 2:
        sys.exit(__doc__)
    sets = [paired_rows(args[i], args[i + 1]) for i in range(0, len(args), 2)]
    rows = [r for s in sets for r in s]
    margins = sorted({c["margin"] for _, _, c in rows
                      if c["before"] == "noise" and math.isfinite(c["margin"])
                      and c["margin"] <= THRESHOLD})
    grid = [-math.inf] + [(a + b) / 2 for a, b in zip(margins, margins[1:])] + [math.inf]
    for name, s in zip(args[::2], sets):
        print(f"{name}: product labelled %d, served %d; every failing first round completed: "
              "labelled %d, served %d, completed on %d" % (tally(s, math.inf)[:2]
                                                         + tally(s, -math.inf)))
    held = [[0, 0] for _ in sets]
    for f in range(FOLDS):
        train = [r for r in rows if fold_of(r[0], FOLDS) != f]
        bound = choose(train, grid)
        line = []
        for k, s in enumerate(sets):
            test = [r for r in s if fold_of(r[0], FOLDS) == f]
            a, b, _ = tally(test, bound)
            held[k][0] += a
            held[k][1] += b
            line.append(f"{a}/{b}")
        print(f"fold {f}: L = {bound:.3f}; held out labelled/served per set: {', '.join(line)}")
    for name, (a, b) in zip(args[::2], held):
        print(f"held out, {name}: labelled {a}, served {b}")
    bound = choose(rows, grid)
    print(f"whole sets: L = {bound:.3f}; " + "; ".join(
        "labelled %d, served %d, completed on %d" % tally(s, bound) for s in sets))


if __name__ == "__main__":
    main()
