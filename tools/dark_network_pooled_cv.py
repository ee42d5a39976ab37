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

Criterion, fixed before any fold was scored: the sum over the training pools of structured
labelled rate + stochastic served rate (each pool weighs as much as the other, and in each a
structured quadrant and a stochastic one by their class's size: the issue judges both rates).
A pool's rates are over all its quadrants: the corpus run may hold only the textures the rule can
touch, with `--sizes` giving the whole corpus's class sizes by fold (the untouched quadrants add
the same to every threshold). Folds: 4 by file (devset::fold_of) within each pool; a held-out fold
of both pools is scored with the threshold chosen on the other three of both. Ties: the
strictest threshold among the best (the fewest quadrants decided by a cue the rule reads alone).

With --gate, a second cue gates the rule (nested: the cue, its direction and threshold chosen on
the training folds with the skewness threshold): the rule decides only where that cue is also
below (or above) its threshold. The cues are the columns of the dark-network laboratory's TSV
(`cargo run --release -p proctex-analyzer --example dark_network_lab -- SET`), one per run.

Usage: tools/dark_network_pooled_cv.py DEV_RUN CORPUS_RUN CORPUS_MANIFEST [UNSEEN_RUN ...]
           [--gate DEV_LAB CORPUS_LAB [UNSEEN_LAB ...]]
  (CORPUS_MANIFEST: the whole corpus's manifest.tsv, for the class sizes by fold)
"""
import sys

from devset_occam_cv import fold_of, noise_and_best, patch_overall, quadrants

T0 = -0.599  # retrieve::DARK_NETWORK_SKEWNESS, the threshold the runs were made with
SKEWNESS = 7  # proctex::cues::SKEWNESS in photo_cues
FOLDS = 4
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


def sizes_of(rows):
    """Structured and stochastic quadrants by fold."""
    s = [[0, 0] for _ in range(FOLDS)]
    for r in rows:
        s[fold_of(r["file"], FOLDS)][r["labels"] == ["noise"]] += 1
    return s


def manifest_sizes(path):
    s = [[0, 0] for _ in range(FOLDS)]
    for line in open(path).read().splitlines()[1:]:
        f = line.split("\t")
        s[fold_of(f[0], FOLDS)][f[1] == "stochastic"] += 4
    return s


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


def criterion(pools, folds, cand, counts=None):
    """Σ over pools of labelled rate + served rate on `folds`, up to a constant: only the quadrants
    the rule decides in the run can change (the corpus run may hold only those it can touch).
    With `counts` (labelled, served) the rates of those counts over the pool's whole `folds`."""
    total = 0.0
    for rows, sizes in pools:
        part = [r for r in rows if r["decided"] and fold_of(r["file"], FOLDS) in folds]
        lab, srv = counts or tally(part, cand)
        total += lab / max(sum(sizes[f][0] for f in folds), 1) \
            + srv / max(sum(sizes[f][1] for f in folds), 1)
    return total


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


def choose(pools, folds, cands):
    scored = [(criterion(pools, folds, c), i) for i, c in enumerate(cands)]
    best = max(s for s, _ in scored)
    # Ties: the strictest (the rule deciding the fewest training quadrants), then the first.
    tied = [cands[i] for s, i in scored if s >= best - 1e-12]
    decided = [r for rows, _ in pools for r in rows
               if r["decided"] and fold_of(r["file"], FOLDS) in folds]
    return min(tied, key=lambda c: sum(keeps(r, c) for r in decided))


def show(cand):
    t, gate = cand
    s = "off" if t == float("-inf") else f"{t:.2f}"
    if gate:
        s += f" & {gate[0]} {'<' if gate[1] else '>='} {gate[2]:.3f}"
    return s


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
    dev, corpus, unseen = rows[0], rows[1], list(zip(args[3:], rows[2:]))
    pools = [(dev, sizes_of(dev)), (corpus, manifest_sizes(args[2]))]
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
    # Two procedures, each scored where it did not choose: chosen on both pools' training folds,
    # and chosen on the development set's training folds alone (the corpus is then all held out).
    for title, train in [("both pools", pools), ("the development set alone", pools[:1])]:
        chosen, held = [], {"dev": [0, 0], "corpus": [0, 0]}
        for f in range(FOLDS):
            c = choose(train, [g for g in range(FOLDS) if g != f], cands)
            chosen.append(c)
            for key, rs in [("dev", dev), ("corpus", corpus)]:
                a, b = tally([r for r in rs if fold_of(r["file"], FOLDS) == f], c)
                held[key] = [held[key][0] + a, held[key][1] + b]
        score = sum(criterion([(rs, sz)], list(range(FOLDS)), None, held[k])
                    for (rs, sz), k in zip(pools, ["dev", "corpus"]))
        print(f"chosen on {title}: folds {'; '.join(show(c) for c in chosen)}; all folds "
              f"{show(choose(train, list(range(FOLDS)), cands))}")
        print(f"  held out: development set {held['dev'][0]} / {held['dev'][1]}, corpus "
              f"{held['corpus'][0]} / {held['corpus'][1]}; criterion {score:.4f}")
        for name, rs in unseen:
            print(f"  {name} at the folds' choices: "
                  + "; ".join("%s: %d / %d" % ((show(c),) + tally(rs, c)) for c in chosen))


if __name__ == "__main__":
    main()
