#!/usr/bin/env python3
"""Cross-validates the noise model's margin and the dark-network threshold again, jointly, under
the product's family order, offline.

Input: the JSON lines of `proctex fidelity --set ../shared/photos/dev --json` (every family fitted
and recorded). The choices are those of `devset_family_order_cv.choose` with the product's order
(the first RENDER_ORDERED families by structure distance reordered at TEXTURE_WEIGHT) and a
margin and threshold of the grids (the script first checks that the product's constants
reproduce the run's choices).

Protocol: 4 folds by devset::fold_of; on each held-out fold, (margin, threshold) is chosen on the
other three (the most structured patches labelled among the pairs that keep ≥ 95 % of the
stochastic patches served; ties to more served, then to the margin nearest the product's), and
scored on the fold.

Usage: tools/devset_margin_dark_cv.py RUN.jsonl
"""
import json
import sys

from devset_family_order_cv import (DARK_NETWORK_SKEWNESS, OCCAM, RENDER_ORDERED, TEXTURE_WEIGHT,
                                    choose, cross_validate, patches, tally)

MARGINS = [x / 20 for x in range(21)]
THRESHOLDS = [-2.0 + x * 0.05 for x in range(41)] + [-9.0]  # −9: no dark network


def main():
    photos = [json.loads(line)["photo"] for line in open(sys.argv[1]) if '"photo"' in line]
    pts = patches(photos)
    order = (TEXTURE_WEIGHT, RENDER_ORDERED)
    agree = sum(choose(pt, *order) == pt["chosen"] for pt in pts)
    print(f"{len(photos)} photos, {len(pts)} patches; the product's constants reproduce "
          f"{agree}/{len(pts)} choices")
    pairs = [(m, d) for m in MARGINS for d in THRESHOLDS]
    folds, pooled, base = cross_validate(
        pts, pairs, lambda ps, c: tally(ps, *order, *c),
        lambda c, t: (t[2], -abs(c[0] - OCCAM)), (OCCAM, DARK_NETWORK_SKEWNESS))
    for f, (m, d), held, b in folds:
        print(f"fold {f}: margin {m:.2f}, threshold {d:.2f} chosen on the others; held out "
              f"structured labelled {held[0]}/{held[1]} (product {b[0]}), stochastic served "
              f"{held[2]}/{held[3]} (product {b[2]}; threshold {DARK_NETWORK_SKEWNESS})")
    print(f"held-out folds pooled: structured labelled {pooled[0]}/{pooled[1]} (product "
          f"{base[0]}), stochastic served {pooled[2]}/{pooled[3]} (product {base[2]})")


if __name__ == "__main__":
    main()
