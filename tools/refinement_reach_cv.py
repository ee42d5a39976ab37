#!/usr/bin/env python3
"""Cross-validates the refinement's bound (retrieve::refinement_reach) on the development set.

Input: the JSON lines of `analyzer/examples/refinement_reach.rs` (per patch, per family: the
retrieval distance, short refinements and the full refinement's distance, every family refined).

The bound (retrieve::Suggester::pending) refines families in rounds: the first RANKS_KEPT by
retrieval distance, then every family whose retrieval distance times its reach is at most the
RANKS_KEPT-th best refined distance so far, until none is. A family's reach is the least
refined / retrieval ratio of that family over the training patches (the most refinement ever
lowered it), rounded down to two decimals. A skipped family keeps its retrieval distance.

Protocol: F folds by devset::fold_of (FNV-1a of the file name); each held-out fold is bounded
with the table of the other folds and compared with refining every family: the same first
model, the same ordered top three, and the families refined. The held-out folds are pooled.
`--also FILE…` bounds other sets (e.g. the shipped samples) with the whole set's table.
`--manifest M` also prints what refinement buys on the structured patches: the best family
(no noise model) in the photo's labelled families when the families are ordered by retrieval
distance, by each short refinement, and by the full refinement.

Usage: tools/refinement_reach_cv.py DEV.jsonl [--folds F] [--quantile Q] [--manifest M]
       [--also FILE…]
"""
import json
import math
import sys

from devset_occam_cv import fold_of

RANKS_KEPT = 3  # retrieve::RANKS_KEPT


def load(path):
    return [json.loads(line) for line in open(path) if line.strip()]


def reach_table(rows, quantile=0.0):
    ratios = {}
    for r in rows:
        for f in r["families"]:
            ratios.setdefault(f["name"], []).append(f["full"] / f["retrieval"])
    table = {}
    for name, v in ratios.items():
        v.sort()
        x = v[min(len(v) - 1, int(quantile * len(v)))]
        table[name] = math.floor(x * 100) / 100
    return table


def bounded(row, table):
    """The families in rank order under the bound, and how many were refined."""
    fams = sorted(row["families"], key=lambda f: f["retrieval"])
    value = {f["name"]: f["retrieval"] for f in fams}
    done = set()
    batch = fams[:RANKS_KEPT]
    while batch:
        for f in batch:
            value[f["name"]] = f["full"]
            done.add(f["name"])
        refined = sorted(value[n] for n in done)
        bound = refined[RANKS_KEPT - 1] if len(refined) >= RANKS_KEPT else math.inf
        batch = [f for f in fams if f["name"] not in done
                 and f["retrieval"] * table.get(f["name"], 0.0) <= bound]
    return sorted(value, key=value.get), len(done)


def full_order(row):
    return [f["name"] for f in sorted(row["families"], key=lambda f: f["full"])]


def compare(rows, table_of):
    first = top3 = 0
    counts = []
    for r in rows:
        order, n = bounded(r, table_of(r))
        full = full_order(r)
        first += order[0] == full[0]
        top3 += order[:3] == full[:3]
        counts.append(n)
    m = sum(counts) / len(counts)
    se = math.sqrt(sum((c - m) ** 2 for c in counts) / max(1, len(counts) - 1) / len(counts))
    return first, top3, m, se, len(rows)


def main():
    args = sys.argv[1:]
    if not args:
        sys.exit(__doc__)
    folds, quantile, manifest, also = 4, 0.0, None, []
    dev = args.pop(0)
    while args:
        a = args.pop(0)
        if a == "--folds":
            folds = int(args.pop(0))
        elif a == "--quantile":
            quantile = float(args.pop(0))
        elif a == "--manifest":
            manifest = args.pop(0)
        elif a == "--also":
            also, args = args, []
        else:
            sys.exit(f"unknown option {a}")
    rows = load(dev)
    tables = [reach_table([r for r in rows if fold_of(r["file"], folds) != k], quantile)
              for k in range(folds)]
    first, top3, m, se, n = compare(rows, lambda r: tables[fold_of(r["file"], folds)])
    print(f"held-out folds ({folds}, reach = {quantile:.0%} quantile): first model as with every "
          f"family refined {first}/{n}, ordered top three {top3}/{n}; "
          f"families refined {m:.2f} ± {se:.2f} of {len(rows[0]['families'])}")
    for k, t in enumerate(tables):
        print(f"  fold {k} table: " + ", ".join(f"{name} {v:.2f}" for name, v in sorted(t.items())))
    whole = reach_table(rows, quantile)
    print("whole set's table: " + ", ".join(f"{name} {v:.2f}" for name, v in sorted(whole.items())))
    for path in also:
        first, top3, m, se, n = compare(load(path), lambda r: whole)
        print(f"{path}: first model {first}/{n}, top three {top3}/{n}; "
              f"families refined {m:.2f} ± {se:.2f}")
    if manifest:
        labels = {}
        for line in open(manifest).read().splitlines()[1:]:
            cells = line.split("\t")
            labels[cells[0]] = (cells[1], cells[3].split())
        structured = [r for r in rows if labels[r["file"]][0] == "structured"]
        keys = [("retrieval", lambda f: f["retrieval"])]
        for i, e in enumerate(rows[0].get("short_evaluations", [])):
            keys.append((f"short refinement, {e} evaluations", lambda f, i=i: f["short"][i]))
        keys.append(("full refinement", lambda f: f["full"]))
        print("best family labelled (structured patches, no noise model):")
        for name, key in keys:
            hit = sum(min(r["families"], key=key)["name"] in labels[r["file"]][1]
                      for r in structured)
            print(f"  by {name}: {hit}/{len(structured)}")


if __name__ == "__main__":
    main()
