#!/usr/bin/env python3
"""What moves between seeds: runs of the yardstick at several seeds compared patch by patch.

Input: `proctex fidelity --set ../shared/photos/dev --json --first-seed S` runs, one per seed.
Prints:
- each run's summary (structured labelled, top three, stochastic served, speck-clean renders);
- the structured patches labelled at every seed, at none, at some (those listed with their
  choices), and how many change their choice at some seed;
- each run's chosen renders over the speck limit (1.5× the photo's own fraction with one pixel
  added to both, `devset::speck_ratio`);
- the nearer-render rule replayed (`devset_nearer_render_cv`) with its margin averaged over the
  runs (offline, a stand-in for a margin measured on as many realisations): where the rule ran
  in a run (the noise model led by score), the mean of the patch's margins over the runs where
  it ran takes the run's margin's place; structured patch-seeds labelled and stochastic ones
  served, per threshold, against the runs' own margins at the same thresholds.

Usage: tools/devset_seeds.py RUN.jsonl RUN.jsonl ...
"""
import json
import math
import sys

from devset_nearer_render_cv import rows_of, tally

SPECK_LIMIT = 1.5
NEARER_RENDER_MARGIN = 1.4801  # retrieve::rules::NEARER_RENDER_MARGIN
THRESHOLDS = [0.5, 0.75, 1.0, 1.25, NEARER_RENDER_MARGIN, 1.75, 2.0, 2.5]


def load(path):
    """The run's summary and its patches by (file, patch): (entry, choice)."""
    patches, summary = {}, None
    for line in open(path):
        d = json.loads(line)
        if "summary" in d:
            summary = d["summary"]
            continue
        p = d["photo"]
        for c in p["choices"]:
            patches[(p["entry"]["file"], c["patch"])] = (p["entry"], c)
    return summary, patches


def main():
    runs = [load(p) for p in sys.argv[1:]]
    if len(runs) < 2:
        sys.exit(__doc__)
    for path, (s, _) in zip(sys.argv[1:], runs):
        rate = lambda k: f"{s[k]['hits']}/{s[k]['total']}"
        print(f"{path}: labelled {rate('structured_labelled')}, top three "
              f"{rate('structured_top3')}, served {rate('stochastic_ok')}, speck-clean "
              f"{rate('specks_clean')}")
    keys = sorted(k for k, (e, _) in runs[0][1].items() if e["category"] == "structured")
    groups = {"every": [], "none": [], "some": []}
    moved = 0
    for k in keys:
        choices = [r[1][k][1]["chosen"] for r in runs]
        labels = runs[0][1][k][0]["families"]
        hits = sum(ch in labels for ch in choices)
        group = "every" if hits == len(runs) else "none" if hits == 0 else "some"
        groups[group].append((k, choices))
        moved += len(set(choices)) > 1
    print(f"\nstructured patches labelled at every seed {len(groups['every'])}, at none "
          f"{len(groups['none'])}, at some {len(groups['some'])}; choice changes at some seed: "
          f"{moved}")
    for g in ("some", "none"):
        print(f"  labelled at {g}:")
        for (f, patch), choices in groups[g]:
            print(f"    {f} {patch}: {' / '.join(choices)}")
    print("\nchosen renders over the speck limit:")
    for path, (_, patches) in zip(sys.argv[1:], runs):
        for (f, patch), (e, c) in sorted(patches.items()):
            floor = 1.0 / c["pixels"]
            ratio = (c["render_specks"] + floor) / (c["photo_specks"] + floor)
            if ratio > SPECK_LIMIT:
                print(f"  {path}: {f} {patch} {c['chosen']} {ratio:.2f}")
    print("\nthe nearer-render rule, its margin per run / averaged over the runs:")
    print("  threshold  structured labelled, stochastic served (of patch-seeds)")
    paths = sys.argv[1:]
    per_run = [rows_of(p) for p in paths]
    recorded = {}
    for rows in per_run:
        for photo, _, c in rows:
            if math.isfinite(c["margin"]):
                recorded.setdefault((photo, c["patch"]), []).append(c["margin"])
    mean = {k: sum(m) / len(m) for k, m in recorded.items()}
    averaged = [rows_of(p, {(photo, c["patch"]): mean.get((photo, c["patch"]), -math.inf)
                            for photo, _, c in rows})
                for p, rows in zip(paths, per_run)]
    structured = sum(labels != ["noise"] for rows in per_run for _, labels, _ in rows)
    stochastic = sum(len(rows) for rows in per_run) - structured
    for t in THRESHOLDS:
        out = []
        for runs_rows in (per_run, averaged):
            labelled, served = (sum(x) for x in zip(*(tally(rows, t) for rows in runs_rows)))
            out.append(f"{labelled}/{structured}, {served}/{stochastic}")
        print(f"  {t:9.4f}  {out[0]:>18} / {out[1]}")

if __name__ == "__main__":
    main()
