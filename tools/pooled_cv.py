"""One ranking rule's setting cross-validated over several labelled sets ("pools") together, and
the same search on the first pool (the development set) alone, each scored where it did not
choose; then replayed on sets neither chose on. Used by dark_network_pooled_cv.py and
nearer_render_pooled_cv.py, which say how their rule is replayed from a run.

Criterion, fixed before any fold was scored: the sum over the training pools of the structured
labelled rate and the stochastic served rate (each pool weighs as much as the other, and in each
a structured quadrant and a stochastic one by their class's size: the issue judges both rates).
Folds: 4 within each pool by file (devset::fold_of), except the training corpus's, drawn by
texture stem (`by_stem`, as corpus_lab's folds: a texture's variants held out together; by file
they sat on both sides of a fold, docs/devset.md "Folds by texture stem"); a held-out fold of
every pool is scored with the setting chosen on the other three of all. Ties: the setting that
moves the fewest training quadrants away from the run's choices' rule-free state (the rule's
`moved`), then the first.

A rule is an object with:
  tally(rows, cand) -> (structured labelled, stochastic served) of `rows` under setting `cand`;
  relevant(row) -> whether the setting can change the row (the others add the same to every
      setting, so a pool's run may hold only the relevant part of a set, with its class sizes
      from the whole set);
  moved(rows, cand) -> how many of `rows` the rule decides under `cand`;
  show(cand) -> the setting in words.
Rows are dicts with at least `file`.
"""
import re

from devset_occam_cv import fold_of

FOLDS = 4


def stem_key(file):
    """A corpus texture's stem as corpus_lab's `lab_common::corpus_files::stem` and `corpus_fold`
    hash it: the folder part of the name (before the last `__`) kept whole, and the file name up to
    its first digit."""
    name = file.rsplit(".", 1)[0]
    folder, _, name = name.rpartition("__")
    m = re.search(r"\d", name)
    return folder + "__" + (name[:m.start()] if m else name)


def by_stem(rows):
    """The training corpus's rows, each to be folded by its texture's stem."""
    for r in rows:
        r["fold_key"] = stem_key(r["file"])
    return rows


def row_fold(r):
    return fold_of(r.get("fold_key", r["file"]), FOLDS)


def sizes_of(rows):
    """Structured and stochastic quadrants by fold."""
    s = [[0, 0] for _ in range(FOLDS)]
    for r in rows:
        s[row_fold(r)][r["labels"] == ["noise"]] += 1
    return s


def manifest_sizes(path, stem=False):
    """Structured and stochastic quadrants by fold of a whole set, from its manifest.tsv (folded by
    texture stem with `stem`, as `by_stem`'s rows)."""
    s = [[0, 0] for _ in range(FOLDS)]
    for line in open(path).read().splitlines()[1:]:
        f = line.split("\t")
        s[fold_of(stem_key(f[0]) if stem else f[0], FOLDS)][f[1] == "stochastic"] += 4
    return s


def tally_first(rows, first, served_ok="measured_ok"):
    """(structured labelled, stochastic served) of `rows` whose first model `first(row)` gives: a
    stochastic row (labels ["noise"]) is served by the noise model, or by the family the run chose
    where the run measured it no farther than the noise model (`row[served_ok]`); another family's
    fidelity was not measured, so it counts as not served."""
    labelled = served = 0
    for r in rows:
        chosen = first(r)
        if r["labels"] == ["noise"]:
            served += chosen == "noise" or (chosen == r["chosen"] and r[served_ok])
        else:
            labelled += chosen in r["labels"]
    return labelled, served


def in_folds(rows, folds):
    return [r for r in rows if row_fold(r) in folds]


def criterion(rule, pools, folds, cand, counts=None):
    """Σ over `pools` ((rows, sizes) each) of labelled rate + served rate on `folds`, up to a
    constant; with `counts` (one (labelled, served) per pool) those counts' rates instead."""
    total = 0.0
    for k, (rows, sizes) in enumerate(pools):
        lab, srv = counts[k] if counts else rule.tally(
            [r for r in in_folds(rows, folds) if rule.relevant(r)], cand)
        total += lab / max(sum(sizes[f][0] for f in folds), 1) \
            + srv / max(sum(sizes[f][1] for f in folds), 1)
    return total


def choose(rule, pools, folds, cands):
    scored = [(criterion(rule, pools, folds, c), i) for i, c in enumerate(cands)]
    best = max(s for s, _ in scored)
    tied = [cands[i] for s, i in scored if s >= best - 1e-12]
    relevant = [r for rows, _ in pools for r in in_folds(rows, folds) if rule.relevant(r)]
    return min(tied, key=lambda c: rule.moved(relevant, c))


def report(rule, pools, names, cands, unseen):
    """Prints both procedures' held-out numbers on every pool and their criterion, the settings
    the folds chose, and those settings replayed on `unseen` ((name, rows) each)."""
    everything = list(range(FOLDS))
    for title, train in [("every pool", pools), (f"the {names[0]} alone", pools[:1])]:
        chosen, held = [], [[0, 0] for _ in pools]
        for f in range(FOLDS):
            c = choose(rule, train, [g for g in everything if g != f], cands)
            chosen.append(c)
            for k, (rows, _) in enumerate(pools):
                a, b = rule.tally(in_folds(rows, [f]), c)
                held[k] = [held[k][0] + a, held[k][1] + b]
        score = criterion(rule, pools, everything, None, held)
        print(f"chosen on {title}: folds {'; '.join(rule.show(c) for c in chosen)}; all folds "
              f"{rule.show(choose(rule, train, everything, cands))}")
        print("  held out (labelled / served): " + ", ".join(
            f"{name} {h[0]} / {h[1]}" for name, h in zip(names, held))
            + f"; criterion {score:.4f}")
        for name, rows in unseen:
            print(f"  {name} at the folds' settings: " + "; ".join(
                "%s: %d / %d" % ((rule.show(c),) + rule.tally(rows, c)) for c in chosen))
