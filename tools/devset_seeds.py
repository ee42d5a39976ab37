#!/usr/bin/env python3
"""What moves between seeds: runs of the yardstick at several seeds compared patch by patch.

Input: `proctex fidelity --set ../shared/photos/dev --json --first-seed S` runs, one per seed.
Prints:
- each run's summary (structured labelled, top three, stochastic served, speck-clean renders);
- the structured patches labelled at every seed, at none, at some (those listed with their
  choices), and how many change their choice at some seed;
- each run's chosen renders over the speck limit (1.5× the photo's own fraction with one pixel
  added to both, `devset::speck_ratio`);
- the nearer-render rule with its margin averaged over the runs (offline, a stand-in for a
  margin measured on as many realisations): where the rule ran in a run (the noise model led by
  score), the classifier's nearest family first when the mean of the patch's margins over the
  runs where it ran exceeds the threshold, else the noise model; labelled over every
  patch-seed, and the stochastic patch-seeds moved off the noise model, per threshold, against
  the runs' own margins at the same thresholds.

Usage: tools/devset_seeds.py RUN.jsonl RUN.jsonl ...
"""
import json
import sys

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


def margin(c):
    d = c["nearer_render_distances"]
    return None if d is None else d[0] - d[1]


def nearest_family(c):
    return next(x for x in c["classifier"] if x != "noise")


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
    print("  threshold  labelled (of patch-seeds)  stochastic patch-seeds off the noise model")
    total = len(keys) * len(runs)
    for t in THRESHOLDS:
        out = []
        for averaged in (False, True):
            labelled = off = 0
            for k in runs[0][1]:
                ms = [m for m in (margin(r[1][k][1]) for r in runs) if m is not None]
                for _, patches in runs:
                    e, c = patches[k]
                    m = margin(c)
                    if m is None:
                        chosen = c["chosen"]
                    else:
                        m = sum(ms) / len(ms) if averaged else m
                        chosen = nearest_family(c) if m > t else "noise"
                    if e["category"] == "structured":
                        labelled += chosen in e["families"]
                    else:
                        off += chosen != "noise" and c["chosen"] == "noise"
            out.append(f"{labelled}/{total} {off}")
        print(f"  {t:9.4f}  {out[0]:>12} / {out[1]:<12}")


if __name__ == "__main__":
    main()
