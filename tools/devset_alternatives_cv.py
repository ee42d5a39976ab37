#!/usr/bin/env python3
"""The order of the ranking after its first row (retrieve::Suggester::ranked), cross-validated
on the development set, offline.

The ranking fits the classifier's first three families and scores each (the blend of structure
and texture distance, the classifier's term, the margin). Which row comes first (the best
family, the noise model, or the classifier's nearest family by the render-null and nearer-render
rules) is taken from the run as recorded: every order below keeps it, so the labelled and served
rates are the run's by construction, and only which rows follow it, hence the top three, differ.
Every number is in the run's JSON (`ranking` scores, `classifier`), so no new analysis is needed.

Orders compared (the fitted families after the first / the noise model when it is not first):
  classifier, after       the classifier's order; the noise model after the fitted families
                          (the product from 2026-12-01 to 2026-12-06)
  classifier, score       the classifier's order; the noise model where its score puts it
  score, after            the families by score; the noise model after the fitted families
                          (the product since 2026-12-06)
  score, score            every candidate by its score (before 2026-12-01)
Where the noise model is first, the best family by score follows it, then the others in the
order named.

Protocol: 4 folds by photo (devset::fold_of); for each held-out fold the order with the most
structured patches having a labelled family among the first three on the other folds (ties: the
earlier in the list above: the product of the day it was run again, 2026-12-06, first), scored
on the held-out fold. Several runs (the whole protocol at other seeds, `--first-seed`) are
pooled: a photo's patches of every run fall in its fold.

Usage: tools/devset_alternatives_cv.py RUN.jsonl [RUN.jsonl...]
"""
import json
import sys

from devset_classifier_weight_cv import DARK_NETWORK_SKEWNESS, FITTED, FOLDS, SKEWNESS
from devset_occam_cv import fold_of, ranking_rows

ORDERS = [("classifier", "after"), ("classifier", "score"), ("score", "after"),
          ("score", "score")]


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
    """The first FITTED + 1 rows (the fitted families and the noise model) under an order, the
    run's first row kept first."""
    f = pt["fitted"]
    first = pt["run"][0]
    by_score = sorted(f, key=lambda n: f[n])
    # The first family: the run's first row, or where the noise model is first the best by score.
    lead = by_score[0] if first == "noise" else first
    if families == "classifier":
        fams = [lead] + [n for n in pt["classifier"] if n in f and n != lead]
    else:
        fams = [lead] + [n for n in by_score if n != lead]
    if first == "noise":
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
    pts = []
    for run in sys.argv[1:]:
        photos = [json.loads(l)["photo"] for l in open(run) if '"photo"' in l]
        pts += patches(photos)
    for o in ORDERS:
        agree = sum(order(pt, *o) == pt["run"] for pt in pts)
        lab, top3, ns = tally(pts, o)
        print(f"{o[0]:>10}, {o[1]:<5}: reproduces the runs' first four rows on {agree}/{len(pts)} "
              f"patches; whole set (for reading) labelled first {lab}/{ns}, top three {top3}/{ns}")
    pooled = [0, 0, 0]
    for k in range(FOLDS):
        train = [pt for pt in pts if fold_of(pt["file"], FOLDS) != k]
        test = [pt for pt in pts if fold_of(pt["file"], FOLDS) == k]
        o = pick(train)
        t = tally(test, o)
        b = tally(test, ORDERS[0])
        pooled = [a + x for a, x in zip(pooled, t)]
        print(f"fold {k}: chose {o}; held out top three {t[1]}/{t[2]} (the first order listed: "
              f"{b[1]}/{b[2]}), labelled first {t[0]}")
    print(f"held-out folds pooled: top three {pooled[1]}/{pooled[2]}, labelled first "
          f"{pooled[0]}/{pooled[2]}; the whole set's choice {pick(pts)}")


if __name__ == "__main__":
    main()
