#!/usr/bin/env python3
"""Which families the ranking fits and orders: those nearest by structure distance, or those the
family classifier (analyzer/src/family_classifier.rs, trained on real textures, never on the
development set) puts first. Recomputes the product's ranking (retrieve::Suggester::ranked)
from one development-set run's recorded distances for each way, and cross-validates the choice
between them.

Ways:
  structure   the three families nearest by structure distance (the product before the classifier)
  classifier  the classifier's first three families
  classifier+ the classifier's first three, and the family it does not know (turbulence, rings)
              nearest by structure distance when nearer than those three
  classifier+nearest
              the classifier's first three, and the family nearest by retrieval distance where
              it is not among them (the product now: the classifier does not know clean
              procedural patterns, and the synthetic round trip's are; retrieve::Suggester)

The fitted families are ordered by 0.9 texture + 0.1 structure distance (retrieve::TEXTURE_WEIGHT)
plus the margin, the noise model placed against the best of them as the product does (after the
fitted families on a dark network: retrieve::DARK_NETWORK_SKEWNESS); the others follow. A run
recorded before the classifier had every family's texture distance and the structure distances
of the families its rounds refined (others: retrieval distance); the classifier's families not
refined there were refined in the product (a full run measures that).

Protocol: 4 folds by photo (devset::fold_of); for each held-out fold the way with the most
structured patches labelled on the other three folds among those keeping >= 95 % of their
stochastic patches served (ties: the first in the list above), scored on the held-out fold. A stochastic patch counts as served when
the noise model is first, or the family the run chose and measured no farther than the noise
model (a family the run did not choose: not served, conservatively).

Usage: tools/devset_classifier_order_cv.py RUN.jsonl [--dump DUMP]
  RUN.jsonl   `proctex fidelity --set ../shared/photos/dev --json`
  --dump      the classifier's orders from `corpus_lab eval` with CORPUS_LAB_DUMP=1 (stderr), for
              a run recorded before the yardstick recorded them (its `classifier` field)
"""
import json
import math
import sys

from devset_occam_cv import fold_of, patch_overall, tally_orders

SKEWNESS = 7  # cues::CUE_NAMES index of "skewness"
DARK_NETWORK_SKEWNESS = -0.599
TEXTURE_WEIGHT = 0.9
FITTED = 3  # retrieve::RENDER_ORDERED
FOLDS = 4
WAYS = ["structure", "classifier", "classifier+", "classifier+nearest"]
# The lab's dump lists the patches top-left, top-right, bottom-left, bottom-right.
DUMP_ORDER = ["top-left", "top-right", "bottom-left", "bottom-right"]


def structure(r):
    return r["refined"] if r["refined"] is not None else r["retrieval"]


def load(run, dump):
    orders = {}
    if dump:
        for line in open(dump):
            if line.startswith("dump\t"):
                _, f, o = line.rstrip("\n").split("\t")
                orders.setdefault(f, []).append([x.split(":")[0] for x in o.split(",")])
    pts = []
    for line in open(run):
        if '"photo"' not in line:
            continue
        p = json.loads(line)["photo"]
        e = p["entry"]
        for i, c in enumerate(p["choices"]):
            cls = orders[e["file"]][DUMP_ORDER.index(c["patch"])] if dump else c["classifier"]
            pts.append(dict(
                file=e["file"], category=e["category"], labels=e["families"] or [],
                chosen=c["chosen"], ranking=c["ranking"], cls=cls,
                dark=c["photo_cues"][SKEWNESS] < DARK_NETWORK_SKEWNESS,
                family_ok=patch_overall(p["auto"], i) <= patch_overall(p["noise"], i)))
    return pts


def order(pt, way):
    rk = {r["name"]: r for r in pt["ranking"]}
    families = sorted((r for r in pt["ranking"] if r["name"] != "noise"), key=structure)
    margin = families[-1]["score"] - structure(families[-1])
    by_structure = [r["name"] for r in families]
    known = [n for n in pt["cls"] if n != "noise" and n in rk]
    if way == "structure":
        fit = by_structure[:FITTED]
    else:
        fit = known[:FITTED]
        unknown = [n for n in by_structure if n not in known]
        if way == "classifier+" and unknown and \
                structure(rk[unknown[0]]) < min(structure(rk[n]) for n in fit):
            fit = fit + unknown[:1]
        nearest = min(families, key=lambda r: r["retrieval"])["name"]
        if way == "classifier+nearest" and nearest not in fit:
            fit = fit + [nearest]
    head = sorted((TEXTURE_WEIGHT * rk[n]["distance"] + (1 - TEXTURE_WEIGHT) * structure(rk[n])
                   + margin, rk[n]["distance"], n) for n in fit)
    best_score, best_texture, _ = head[0]
    if pt["dark"]:
        noise_score = math.nextafter(head[-1][0], math.inf)
    else:
        noise_score = rk["noise"]["distance"] - (best_texture - best_score) - margin
    ranked = [n for _, _, n in sorted(head + [(noise_score, 0.0, "noise")])]
    rest = by_structure if way == "structure" else known + by_structure
    return ranked + [n for n in dict.fromkeys(rest) if n not in ranked]


def tally(pts, way):
    return tally_orders(pts, lambda pt: order(pt, way))


def main():
    args = sys.argv[1:]
    dump = None
    if "--dump" in args:
        k = args.index("--dump")
        dump = args[k + 1]
        del args[k:k + 2]
    pts = load(args[0], dump)
    print("whole set (labelled, top three of structured; served of stochastic), then per fold:")
    for way in WAYS:
        lab, top3, ns, served, nt = tally(pts, way)
        folds = [tally([p for p in pts if fold_of(p["file"], FOLDS) == k], way)[:2]
                 for k in range(FOLDS)]
        print(f"  {way:<18} labelled {lab}/{ns}, top three {top3}/{ns}, served {served}/{nt}; "
              f"folds {folds}")
    held = [0, 0, 0, 0, 0]
    for k in range(FOLDS):
        train = [p for p in pts if fold_of(p["file"], FOLDS) != k]
        test = [p for p in pts if fold_of(p["file"], FOLDS) == k]
        ok = [w for w in WAYS if (lambda t: t[3] >= 0.95 * t[4])(tally(train, w))] or WAYS
        way = max(ok, key=lambda w: tally(train, w)[0])
        t = tally(test, way)
        held = [a + b for a, b in zip(held, t)]
        print(f"  fold {k}: chose {way}; held out labelled {t[0]}/{t[2]}, top three {t[1]}/{t[2]}, "
              f"served {t[3]}/{t[4]}")
    lab, top3, ns, served, nt = held
    print(f"held-out folds pooled: labelled {lab}/{ns}, top three {top3}/{ns}, served {served}/{nt}")


if __name__ == "__main__":
    main()
