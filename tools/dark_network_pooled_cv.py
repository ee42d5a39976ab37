#!/usr/bin/env python3
"""The dark-network threshold (retrieve::DARK_NETWORK_SKEWNESS) cross-validated over the
development set and the classifier's labelled training textures together, then replayed on a set
neither chose it on.

The development set has 4 stochastic quadrants (of 108) whose detrended luminance is skewed below
the threshold, so its folds cannot learn what the rule costs on stained, pitted and dirty
surfaces; the training corpus (tools/corpus/labels*.tsv: 590 labelled game textures, 234 of them
with a quadrant skewed below -0.35) has 234 such stochastic quadrants of 1452.

Each quadrant of a run (`proctex fidelity --set SET --json`, made with the product's threshold
T0 = -0.599) is replayed at a stricter threshold T <= T0: where the rule decided it (skewness
below T0 and the noise model's texture score no worse than the best family's: the rule put the
family first), a skewness at or above T gives the noise model instead (served, not labelled).
Thresholds above T0 are not replayed (the run has no fidelity for a family the rule would newly
put first), so the search can only make the rule stricter or turn it off.

The search (tools/pooled_cv.py): the pools' labelled and served rates summed, 4 folds in each
(the development set's by file, the corpus's by texture stem), against the same search on the
development set alone. The corpus run may hold only the textures the rule can touch, with
CORPUS_MANIFEST giving the whole corpus's class sizes by fold (the untouched quadrants add the
same to every threshold). Ties: the strictest threshold among the best (the fewest quadrants
decided by a cue the rule reads alone).

With --gate, a second cue gates the rule (nested: the cue, its direction and threshold chosen on
the training folds with the skewness threshold): the rule decides only where that cue is also
below (or above) its threshold. The cues are the columns of the dark-network laboratory's TSV
(`cargo run --release -p proctex-analyzer --example dark_network_lab -- SET`), one per run.

Usage: tools/dark_network_pooled_cv.py DEV_RUN CORPUS_RUN CORPUS_MANIFEST [UNSEEN_RUN ...]
           [--gate DEV_LAB CORPUS_LAB [UNSEEN_LAB ...]]
  (CORPUS_MANIFEST: the whole corpus's manifest.tsv, for the class sizes by fold)
"""
import sys

import pooled_cv
from devset_occam_cv import noise_and_best, patch_overall, quadrants

T0 = -0.599  # retrieve::DARK_NETWORK_SKEWNESS, the threshold the runs were made with
SKEWNESS = 7  # proctex::cues::SKEWNESS in photo_cues
GRID = [T0] + [round(-0.6 - 0.05 * k, 2) for k in range(1, 29)] + [float("-inf")]


def rows_of(run, lab=None):
    """The run's quadrants; with `lab` (a dark_network_lab TSV of the same set) their lab cues."""
    cues = {}
    if lab:
        lines = open(lab).read().splitlines()
        head = lines[0].split("\t")
        for line in lines[1:]:
            f = line.split("\t")
            cues[(f[0], f[1])] = {k: float(v) for k, v in zip(head[4:], f[4:])}
    rows = []
    for p, i, c in quadrants(run):
        noise, best = noise_and_best(c)
        skew = c["photo_cues"][SKEWNESS]
        rows.append(dict(
            file=p["entry"]["file"], labels=p["entry"]["families"], chosen=c["chosen"],
            skew=skew, decided=skew < T0 and noise["score"] <= best["score"],
            cues=cues.get((p["entry"]["file"], c["patch"]), {}),
            served=c["chosen"] == "noise"
            or patch_overall(p["auto"], i) <= patch_overall(p["noise"], i)))
    return rows


def keeps(r, cand):
    """Whether the rule still decides quadrant `r` under candidate (t, gate)."""
    t, gate = cand
    if r["skew"] >= t:
        return False
    if gate is None:
        return True
    cue, below, g = gate
    return (r["cues"][cue] < g) == below


def tally(rows, cand):
    """(structured labelled, stochastic served) of `rows` under candidate (t, gate)."""
    labelled = served = 0
    for r in rows:
        chosen = "noise" if r["decided"] and not keeps(r, cand) else r["chosen"]
        if r["labels"] == ["noise"]:
            served += chosen == "noise" or r["served"]
        else:
            labelled += chosen in r["labels"]
    return labelled, served


def candidates(pools, gate):
    """(t, None) for every t in GRID; with `gate`, also every lab cue's deciles over the decided
    quadrants, below and above, at every t."""
    out = [(t, None) for t in GRID]
    if gate:
        decided = [r for rows, _ in pools for r in rows if r["decided"]]
        for cue in decided[0]["cues"]:
            values = sorted(r["cues"][cue] for r in decided)
            for k in range(1, 10):
                g = values[k * len(values) // 10]
                out += [(t, (cue, below, g)) for t in GRID for below in (True, False)]
    return out


def show(cand):
    t, gate = cand
    s = "off" if t == float("-inf") else f"{t:.2f}"
    if gate:
        s += f" & {gate[0]} {'<' if gate[1] else '>='} {gate[2]:.3f}"
    return s


class Rule:
    """The dark-network rule for pooled_cv: a setting is (threshold, gate or None)."""
    tally = staticmethod(tally)
    relevant = staticmethod(lambda r: r["decided"])
    moved = staticmethod(lambda rows, cand: sum(r["decided"] and keeps(r, cand) for r in rows))
    show = staticmethod(show)


def main():
    args = sys.argv[1:]
    labs = []
    if "--gate" in args:
        labs = args[args.index("--gate") + 1:]
        args = args[:args.index("--gate")]
    if len(args) < 3:
        sys.exit(__doc__)
    runs = [args[0], args[1]] + args[3:]
    rows = [rows_of(run, labs[i] if labs else None) for i, run in enumerate(runs)]
    dev, corpus, unseen = rows[0], pooled_cv.by_stem(rows[1]), list(zip(args[3:], rows[2:]))
    pools = [(dev, pooled_cv.sizes_of(dev)), (corpus, pooled_cv.manifest_sizes(args[2], stem=True))]
    cands = candidates(pools, bool(labs))
    for name, rs in [("development set", dev), ("corpus", corpus)] + unseen:
        d = [r for r in rs if r["decided"]]
        print(f"{name}: the rule decides {len(d)} quadrants "
              f"({sum(r['labels'] != ['noise'] for r in d)} structured); labelled / served at "
              + ", ".join(f"{show((t, None))} {'%d / %d' % tally(rs, (t, None))}"
                          for t in [T0, -0.8, -1.0, -1.2, float('-inf')]))
    d0, c0 = tally(dev, (T0, None)), tally(corpus, (T0, None))
    print(f"the product ({show((T0, None))}): development set {d0[0]} / {d0[1]}, corpus "
          f"{c0[0]} / {c0[1]} (touchable textures only)")
    pooled_cv.report(Rule, pools, ["development set", "corpus"], cands, unseen)

if __name__ == "__main__":
    main()
