#!/usr/bin/env python3
"""The nearer-render threshold (retrieve::NEARER_RENDER_MARGIN) cross-validated over the
development set and the classifier's labelled training corpus together (tools/pooled_cv.py), then
replayed on sets neither chose it on.

Where the ranking's other rules put the noise model first, the classifier's nearest family comes
first instead when the photo is nearer to that family's fitted render than to the noise model's
in scattering space by more than t (the run's `nearer_render_margin`, recorded on every such
patch). Each patch is replayed at every t between two recorded margins and at "off": a stochastic
patch the replay gives a family is served only where the run chose that same family and measured
it no farther than the noise model (the run did not measure any other family's fidelity), as in
devset_nearer_render_cv.py. Every run must hold its whole set (the rule can act on any patch).

Usage: tools/nearer_render_pooled_cv.py DEV_RUN CORPUS_RUN [UNSEEN_RUN ...]
"""
import math
import sys

import pooled_cv
from devset_occam_cv import patch_overall, quadrants

RUNS = 1.2364  # retrieve::NEARER_RENDER_MARGIN when the runs of docs/devset.md were made (now 1.4801)


def rows_of(run):
    rows = []
    for p, i, c in quadrants(run):
        margin = c.get("nearer_render_margin")
        rows.append(dict(
            file=p["entry"]["file"], labels=p["entry"]["families"], chosen=c["chosen"],
            # The model first before the rule: the noise model wherever a margin was recorded.
            before="noise" if margin is not None else c["chosen"],
            margin=-math.inf if margin is None else margin,
            nearest=next((k for k in c["classifier"] if k != "noise"), None),
            measured_ok=patch_overall(p["auto"], i) <= patch_overall(p["noise"], i)))
    return rows


def chosen_at(r, t):
    if r["before"] == "noise" and r["nearest"] and r["margin"] > t:
        return r["nearest"]
    return r["before"]


class Rule:
    """The nearer-render rule for pooled_cv: a setting is the threshold t (inf: off)."""

    @staticmethod
    def tally(rows, t):
        return pooled_cv.tally_first(rows, lambda r: chosen_at(r, t))

    relevant = staticmethod(lambda r: r["before"] == "noise" and math.isfinite(r["margin"]))
    moved = staticmethod(lambda rows, t: sum(chosen_at(r, t) != r["before"] for r in rows))
    show = staticmethod(lambda t: "off" if t == math.inf else f"{t:.3f}")


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    dev, corpus = rows_of(sys.argv[1]), pooled_cv.by_stem(rows_of(sys.argv[2]))
    unseen = [(run, rows_of(run)) for run in sys.argv[3:]]
    pools = [(dev, pooled_cv.sizes_of(dev)), (corpus, pooled_cv.sizes_of(corpus))]
    at = sorted({r["margin"] for rows, _ in pools for r in rows if Rule.relevant(r)})
    cands = [(a + b) / 2 for a, b in zip(at, at[1:])] + [RUNS, math.inf]
    for name, rows in [("development set", dev), ("corpus", corpus)] + unseen:
        structured = sum(r["labels"] != ["noise"] for r in rows)
        print(f"{name}: {structured} structured, {len(rows) - structured} stochastic quadrants; "
              "labelled / served at the runs' %s: %d / %d, off: %d / %d"
              % ((Rule.show(RUNS),) + Rule.tally(rows, RUNS) + Rule.tally(rows, math.inf)))
    pooled_cv.report(Rule, pools, ["development set", "corpus"], cands, unseen)


if __name__ == "__main__":
    main()
