#!/usr/bin/env python3
"""The order of the ranking after its first family (retrieve::Suggester::ranked), cross-validated
on the development set, offline.

The ranking fits the classifier's first three families and scores each (the blend of structure
and texture distance, the classifier's term, the margin); the best score is the first family.
The noise model's score is its texture distance moved onto the best family's scale; it comes
first when that score is no larger than the best family's (never on a photo with a dark network,
DARK_NETWORK_SKEWNESS). Every number is in the run's JSON (`ranking` scores, `classifier`,
`photo_cues`), so the orders below need no new analysis, and the first model is the same in
every one of them: only which families follow it, hence the top three, differ.

Orders compared (the families after the first / the noise model when it is not first):
  score, score            every candidate by its score (before 2026-12-01)
  classifier, score       the other fitted families in the classifier's order; the noise model
                          keeps the place its score gives it among them
  score, after            the families by score; the noise model after the fitted families
  classifier, after       the classifier's order; the noise model after the fitted families

Protocol: 4 folds by photo (devset::fold_of); for each held-out fold the order with the most
structured patches having a labelled family among the first three on the other folds (ties: the
earlier in the list above), scored on the held-out fold.

Usage: tools/devset_alternatives_cv.py RUN.jsonl
"""
import json
import sys

from devset_classifier_weight_cv import DARK_NETWORK_SKEWNESS, FITTED, FOLDS, SKEWNESS
from devset_occam_cv import fold_of, ranking_rows

ORDERS = [("score", "score"), ("classifier", "score"), ("score", "after"),
          ("classifier", "after")]


def patches(photos):
    out = []
    for p, i, c, noise, fams in ranking_rows(photos):
        e = p["entry"]
        first3 = [n for n in c["classifier"] if n != "noise"][:FITTED]
        fitted = {r["name"]: r["score"] for r in fams if r["name"] in first3}
        out.append(dict(file=e["file"], category=e["category"], labels=e["families"] or [],
                        fitted=fitted, classifier=first3, noise=noise["score"],
                        dark=c["photo_cues"][SKEWNESS] < DARK_NETWORK_SKEWNESS,
                        run=[r["name"] for r in c["ranking"]][:FITTED + 1]))
    return out


def order(pt, families, noise):
    """The first FITTED + 1 rows (the fitted families and the noise model) under an order."""
    f = pt["fitted"]
    by_score = sorted(f, key=lambda n: f[n])
    best = by_score[0]
    if families == "classifier":
        fams = [best] + [n for n in pt["classifier"] if n != best and n in f]
    else:
        fams = by_score
    if not pt["dark"] and pt["noise"] <= f[best]:
        return ["noise"] + fams
    if noise == "after" or pt["dark"]:
        return fams + ["noise"]
    place = 1 + sum(f[n] < pt["noise"] for n in fams[1:])
    return fams[:place] + ["noise"] + fams[place:]


def tally(pts, o):
    """(labelled first, labelled among the first three, structured patches)."""
    lab = top3 = ns = 0
    for pt in pts:
        if pt["category"] != "structured":
            continue
        r = order(pt, *o)
        ns += 1
        lab += r[0] in pt["labels"]
        top3 += any(n in pt["labels"] for n in r[:3])
    return lab, top3, ns


def pick(pts):
    return max(ORDERS, key=lambda o: (tally(pts, o)[1], -ORDERS.index(o)))


def main():
    photos = [json.loads(l)["photo"] for l in open(sys.argv[1]) if '"photo"' in l]
    pts = patches(photos)
    for o in ORDERS:
        agree = sum(order(pt, *o) == pt["run"] for pt in pts)
        print(f"{o[0]:>10}, {o[1]:<5}: reproduces the run's first four rows on {agree}/{len(pts)} "
              "patches; whole set (for reading) labelled first {}/{}, top three {}/{}".format(
                  tally(pts, o)[0], tally(pts, o)[2], tally(pts, o)[1], tally(pts, o)[2]))
    pooled = [0, 0, 0]
    for k in range(FOLDS):
        train = [pt for pt in pts if fold_of(pt["file"], FOLDS) != k]
        test = [pt for pt in pts if fold_of(pt["file"], FOLDS) == k]
        o = pick(train)
        t = tally(test, o)
        b = tally(test, ORDERS[0])
        pooled = [a + x for a, x in zip(pooled, t)]
        print(f"fold {k}: chose {o}; held out top three {t[1]}/{t[2]} (by score: {b[1]}/{b[2]}), "
              f"labelled first {t[0]}")
    print(f"held-out folds pooled: top three {pooled[1]}/{pooled[2]}, labelled first "
          f"{pooled[0]}/{pooled[2]}; the whole set's choice {pick(pts)}")


if __name__ == "__main__":
    main()
