#!/usr/bin/env python3
"""The render-null threshold (retrieve::RENDER_NULL_MARGIN) cross-validated over the development
set and the classifier's labelled training corpus together (tools/pooled_cv.py), then replayed on
sets neither chose it on.

The rule as devset_null_gate_cv.py replays it (its `patches`): where the noise model comes first
by its score, the classifier's nearest family comes first instead when the photo's margin for it
beyond the noise model's render exceeds t; where a fitted family comes first, the nearest comes
first instead when the photo's margin beyond that family's render, and the photo's own, exceed t.
Replayed with the nearer-render rule after it, as the product runs them: where the noise model is
still first, the nearest family comes first when the run recorded a scattering margin above
retrieve::NEARER_RENDER_MARGIN. The run measured that margin only where its own render-null rule
left the noise model first; a quadrant that a higher t leaves to the noise model without a
recorded margin keeps the noise model (counted and printed: `unknown`). A stochastic quadrant the
replay gives a family is served only where the run chose that same family and measured it no
farther than the noise model.

Usage: tools/render_null_pooled_cv.py DEV_RUN CORPUS_RUN [UNSEEN_RUN ...]
"""
import math
import sys

import pooled_cv
from devset_null_gate_cv import patches
from devset_occam_cv import quadrants

RUNS = 9.25  # retrieve::RENDER_NULL_MARGIN when the runs were made
NEARER_RUNS = 1.2364  # retrieve::NEARER_RENDER_MARGIN when the runs were made
NEARER = 1.4801  # retrieve::NEARER_RENDER_MARGIN now


def rows_of(run):
    rows = patches(run, None)
    for r, (_, _, c) in zip(rows, quadrants(run)):
        margin = c.get("nearer_render_margin")
        r["nearer"] = None if margin is None else margin
        r["labels"] = r["labels"] if r["structured"] else ["noise"]
    return rows


def chosen_at(r, t, nearer=NEARER):
    if r["by_score"]:
        if r["beyond"] > t:
            return r["nearest"]
        if r["nearer"] is not None and r["nearer"] > nearer:
            return r["nearest"]
        return "noise"
    if r["family"] is not None:
        return r["nearest"] if r["family"] > t else r["best"]
    return r["chosen"]


def unknown(rows, t):
    """Quadrants left to the noise model at t whose scattering margin the run did not measure."""
    return sum(r["by_score"] and r["beyond"] <= t and r["nearer"] is None and r["beyond"] > RUNS
               for r in rows)


class Rule:
    """The render-null rule for pooled_cv: a setting is the threshold t (inf: off)."""

    @staticmethod
    def tally(rows, t):
        return pooled_cv.tally_first(rows, lambda r: chosen_at(r, t), served_ok="no_worse")

    relevant = staticmethod(lambda r: r["by_score"] or r["family"] is not None)
    moved = staticmethod(lambda rows, t: sum(
        chosen_at(r, t) != chosen_at(r, math.inf) for r in rows))
    show = staticmethod(lambda t: "off" if t == math.inf else f"{t:.3f}")


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    dev, corpus = rows_of(sys.argv[1]), rows_of(sys.argv[2])
    unseen = [(run, rows_of(run)) for run in sys.argv[3:]]
    pools = [(dev, pooled_cv.sizes_of(dev)), (corpus, pooled_cv.sizes_of(corpus))]
    at = sorted({m for rows, _ in pools for r in rows if Rule.relevant(r)
                 for m in (r["beyond"], r["family"]) if m is not None and math.isfinite(m)})
    cands = [(a + b) / 2 for a, b in zip(at, at[1:])] + [RUNS, math.inf]
    for name, rows in [("development set", dev), ("corpus", corpus)] + unseen:
        structured = sum(r["labels"] != ["noise"] for r in rows)
        same = sum(chosen_at(r, RUNS, NEARER_RUNS) == r["chosen"] for r in rows)
        print(f"{name}: {structured} structured, {len(rows) - structured} stochastic quadrants; "
              f"the replay at the runs' thresholds reproduces {same} of {len(rows)} choices; "
              "labelled / served at %s: %d / %d, off: %d / %d (unknown off: %d)"
              % ((Rule.show(RUNS),) + Rule.tally(rows, RUNS) + Rule.tally(rows, math.inf)
                 + (unknown(rows, math.inf),)))
    pooled_cv.report(Rule, pools, ["development set", "corpus"], cands, unseen)


if __name__ == "__main__":
    main()
