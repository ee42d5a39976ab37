#!/usr/bin/env python3
"""The noise model's margin (retrieve::NOISE_MODEL_MARGIN) cross-validated again, jointly with
the render-null threshold (retrieve::RENDER_NULL_MARGIN), offline from one run's JSON.

The ranking puts the noise model first by its score when its texture distance is at most the
best fitted family's plus the margin m (NOISE_MODEL_MARGIN × the patch's self distance); a
margin k × m moves the noise model's score against the best family's by (1 − k) × m. m is read
from the run: an unfitted family's score is its retrieval distance plus m. Every other step is
the render-null rule as tools/devset_null_gate_cv.py replays it (the run's choices reproduced at
k = 1 and the run's tau).

Protocol: 4 folds by photo; on the other three folds the (k, tau) with the most structured
patches labelled among those keeping >= 95 % of their stochastic patches served (ties: the k
nearest the product's, then the larger tau), scored on the held-out fold. A stochastic patch
served by a family the run did not choose counts as not served.

Usage: tools/devset_noise_margin_cv.py RUN.jsonl [--current TAU]
"""
import json
import sys

import devset_null_gate_cv as gate
from devset_occam_cv import fold_of

SCALES = [0, 0.25, 0.5, 0.75, 1, 1.25, 1.5, 2, 3]


def margins(run):
    """Per patch (in the run's order): the margin m and every candidate's score by name."""
    out = []
    for line in open(run):
        if not line.startswith('{"photo"'):
            continue
        for c in json.loads(line)["photo"]["choices"]:
            fitted = [k for k in c["classifier"] if k != "noise"][:gate.FITTED]
            m = next(r["score"] - r["retrieval"] for r in c["ranking"]
                     if r["name"] != "noise" and r["name"] not in fitted
                     and r.get("refined") is None)
            out.append((m, {r["name"]: r["score"] for r in c["ranking"]}))
    return out


def at_scale(pts, k):
    out = []
    for pt in pts:
        q = dict(pt)
        if not q["dark"]:
            q["by_score"] = q["gap"] + (1 - k) * q["m"] <= 0
        out.append(q)
    return out


def tally(pts, tau):
    return gate.tally(pts, "beyond", tau, "nearest", tau)


def main():
    args = sys.argv[1:]
    current = 9.25
    if "--current" in args:
        i = args.index("--current")
        current = float(args[i + 1])
        del args[i:i + 2]
    pts = gate.patches(args[0], None)
    for pt, (m, score) in zip(pts, margins(args[0])):
        pt["m"] = m
        pt["gap"] = score["noise"] - score[pt["best"]]
        # A dark network keeps the noise model after the families whatever the scores.
        pt["dark"] = not pt["by_score"] and pt["gap"] <= 0
    same = sum(gate.choice(pt, "beyond", current, "nearest", current) == pt["chosen"]
               for pt in at_scale(pts, 1))
    print(f"replay at k = 1, tau {current}: {same} of {len(pts)} of the run's choices")
    stochastic = sum(not pt["structured"] for pt in pts)
    for k in SCALES:
        p = at_scale(pts, k)
        ok = [(r, t) for r, t in ((tally(p, t), t) for t in gate.GRID) if r[1] >= 0.95 * stochastic]
        best = max(ok, default=None)
        print(f"k {k}: at tau {current} labelled %d, served %d; best tau over the whole set "
              f"{best[1] if best else None}: labelled %d, served %d"
              % (tally(p, current) + (best[0] if best else (0, 0))))
    held, chosen = [0, 0], []
    for f in range(gate.FOLDS):
        options = []
        for k in SCALES:
            train = [pt for pt in at_scale(pts, k) if fold_of(pt["file"], gate.FOLDS) != f]
            stochastic = sum(not pt["structured"] for pt in train)
            for t in gate.GRID:
                labelled, served = tally(train, t)
                if served >= 0.95 * stochastic:
                    options.append((labelled, -abs(k - 1), t, k))
        _, _, t, k = max(options)
        chosen.append((k, t))
        test = [pt for pt in at_scale(pts, k) if fold_of(pt["file"], gate.FOLDS) == f]
        labelled, served = tally(test, t)
        held[0] += labelled
        held[1] += served
    print(f"held out (k, tau chosen on the other folds {chosen}): labelled {held[0]}, "
          f"served {held[1]}")


if __name__ == "__main__":
    main()
