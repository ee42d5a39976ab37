#!/usr/bin/env python3
"""Summarise `proctex fidelity PHOTO... --model pyramid --against noise --json` by category.

Usage: tools/pyramid_fidelity.py RUN.jsonl MANIFEST.tsv [--per-photo]

For each photo: the Heeger-Bergen synthesis' fidelity ratios (spectrum, colour, structure and
their mean, "overall"), the random-phase floor's and the noise model's (the --against run's
ratios are the pyramid's minus the paired difference). Per category: means with standard
errors over photos, medians, and the mean of ln(pyramid / noise) and ln(pyramid / floor) of the
overall ratio (robust to the tiled photos whose d(A,B) is tiny and every ratio large).
Photos whose fidelity is undefined (quadrants identical: d(A,B) = 0) are left out.
"""
import json
import math
import statistics
import sys


def mean_se(v):
    m = statistics.fmean(v)
    se = statistics.stdev(v) / math.sqrt(len(v)) if len(v) > 1 else float("nan")
    return m, se


def main():
    run, manifest = sys.argv[1], sys.argv[2]
    per_photo = "--per-photo" in sys.argv
    category = {}
    with open(manifest) as f:
        header = f.readline().rstrip("\n").split("\t")
        for line in f:
            cols = dict(zip(header, line.rstrip("\n").split("\t")))
            category[cols["file"]] = cols["category"]
    rows = {}
    with open(run) as f:
        for line in f:
            if not line.startswith("{"):
                continue
            d = json.loads(line)
            r = d["result"]
            if min(r["halves"].values()) <= 0:
                continue
            hb = [r["spectrum_ratio"], r["colour_ratio"], r["structure_ratio"]]
            floor = [r["floor_spectrum_ratio"], r["floor_colour_ratio"], r["floor_structure_ratio"]]
            diff = d["against"]["ratio_difference"]
            noise = [hb[0] - diff["spectrum_db"], hb[1] - diff["colour"], hb[2] - diff["structure"]]
            if not all(map(math.isfinite, hb + floor + noise)):
                continue
            rows.setdefault(category.get(d["photo"], "?"), []).append((d["photo"], hb, floor, noise))
    for cat, items in sorted(rows.items()):
        print(f"{cat}: {len(items)} photos")
        if per_photo:
            for name, hb, floor, noise in items:
                f3 = lambda v: " ".join(f"{x:5.2f}" for x in v + [statistics.fmean(v)])
                print(f"  {name:<40} pyramid {f3(hb)}  floor {f3(floor)}  noise {f3(noise)}")
        for label, idx in [("spectrum", 0), ("colour", 1), ("structure", 2), ("overall", None)]:
            pick = (lambda v: statistics.fmean(v)) if idx is None else (lambda v, i=idx: v[i])
            cols = []
            for k in (1, 2, 3):
                v = [pick(it[k]) for it in items]
                m, se = mean_se(v)
                cols.append(f"{m:.3f} ± {se:.3f} (median {statistics.median(v):.3f})")
            print(f"  {label:<9} pyramid {cols[0]} | floor {cols[1]} | noise {cols[2]}")
        ln_noise = [math.log(statistics.fmean(it[1]) / statistics.fmean(it[3])) for it in items]
        ln_floor = [math.log(statistics.fmean(it[1]) / statistics.fmean(it[2])) for it in items]
        m1, s1 = mean_se(ln_noise)
        m2, s2 = mean_se(ln_floor)
        print(f"  mean ln(pyramid/noise) {m1:+.3f} ± {s1:.3f}; mean ln(pyramid/floor) {m2:+.3f} ± {s2:.3f}")


main()
