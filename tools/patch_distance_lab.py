#!/usr/bin/env python3
"""A patch-distribution distance as the model choice (laboratory): would a distance that compares
the photo's and each render's local patches, at several scales, pick the labelled family where the
ranking's texture distance (Gabor energies of the two-tone map) does not?

Input: the renders of `examples/ranked_renders.rs` (every fitted candidate of the automatic
ranking on every quadrant of the development set, and the quadrant itself) and its TSV.
Distance: sliced Wasserstein (64 fixed random directions, 256 quantiles) between the 5x5 patches
(4000 drawn per image) of the luminance, standardised per image, at each of 4 levels of a Gaussian
pyramid (sigma 1, halved each level); summed over the levels chosen. Choices: the candidate of
least distance among the noise model and the ranking's three fitted families ("fitted3") or among
every candidate ("all"), and among the three fitted families alone (the product's noise decision
aside). Needs numpy, scipy, pillow.

Usage:
  cargo run --release -p proctex-analyzer --example ranked_renders -- ../shared/photos/dev R > R.tsv
  tools/patch_distance_lab.py R.tsv R [CACHE.json]
"""
import json
import os
import sys
from collections import Counter

import numpy as np
from PIL import Image
from scipy import ndimage

PATCH = 5
LEVELS = 4
DIRECTIONS = 64
SAMPLES = 4000
QUANTILES = np.linspace(0, 1, 256)
PAIR = {"tl": "bl", "bl": "tl", "tr": "br", "br": "tr"}


def luminance(path):
    a = np.asarray(Image.open(path).convert("RGB"), dtype=np.float64) / 255.0
    l = a @ np.array([0.2126, 0.7152, 0.0722])
    return (l - l.mean()) / (l.std() + 1e-6)


def pyramid(img):
    out = [img]
    for _ in range(LEVELS - 1):
        out.append(ndimage.gaussian_filter(out[-1], 1.0)[::2, ::2])
    return out


def patches(a, seed):
    h, w = a.shape
    ys, xs = np.arange(h - PATCH + 1), np.arange(w - PATCH + 1)
    n = len(ys) * len(xs)
    idx = np.random.default_rng(seed).choice(n, size=min(SAMPLES, n), replace=False)
    yy, xx = ys[idx // len(xs)], xs[idx % len(xs)]
    off = np.arange(PATCH)
    p = a[yy[:, None, None] + off[None, :, None], xx[:, None, None] + off[None, None, :]]
    return p.reshape(len(idx), -1)


DIRS = np.random.default_rng(11).standard_normal((DIRECTIONS, PATCH * PATCH))
DIRS /= np.linalg.norm(DIRS, axis=1, keepdims=True)


def per_level(a, b):
    out = []
    for level, (x, y) in enumerate(zip(pyramid(a), pyramid(b))):
        if min(x.shape) < PATCH + 4:
            out.append(0.0)
            continue
        qx = np.quantile(patches(x, 1 + level) @ DIRS.T, QUANTILES, axis=0)
        qy = np.quantile(patches(y, 2 + level) @ DIRS.T, QUANTILES, axis=0)
        out.append(float(np.mean((qx - qy) ** 2)))
    return out


def compute(tsv, renders, cache):
    res = json.load(open(cache)) if cache and os.path.exists(cache) else {}
    for line in open(tsv):
        f, q, cat, labels, order = line.rstrip("\n").split("\t")
        key = f + ":" + q
        if key in res:
            continue
        stem = os.path.join(renders, f[:-4])
        photo = luminance(f"{stem}_{q}_photo.png")
        d = {"_self": per_level(photo, luminance(f"{stem}_{PAIR[q]}_photo.png"))}
        for name in order.split(","):
            path = f"{stem}_{q}_{name}.png"
            if os.path.exists(path):
                d[name] = per_level(photo, luminance(path))
        res[key] = {"cat": cat, "labels": labels.split(","), "order": order.split(","), "d": d}
        if cache:
            json.dump(res, open(cache, "w"))
    return res


def main():
    res = compute(sys.argv[1], sys.argv[2], sys.argv[3] if len(sys.argv) > 3 else None)
    structured = [r for r in res.values() if r["cat"] == "structured"]
    stochastic = [r for r in res.values() if r["cat"] != "structured"]
    fams = lambda r: [n for n in r["order"] if n != "noise" and n in r["d"]]
    print(f"product: labelled {sum(r['order'][0] in r['labels'] for r in structured)}/{len(structured)}, "
          f"first family labelled {sum(fams(r)[0] in r['labels'] for r in structured)}, "
          f"stochastic keep noise {sum(r['order'][0] == 'noise' for r in stochastic)}/{len(stochastic)}")
    for levels in ([0], [1], [2], [3], [2, 3], [0, 1, 2, 3]):
        dist = lambda r, n: sum(r["d"][n][l] for l in levels)
        for pool in ("fitted3", "all"):
            cands = lambda r: ["noise"] + fams(r)[:3] if pool == "fitted3" else [n for n in r["d"] if n[0] != "_"]
            pick = lambda r: min(cands(r), key=lambda n: dist(r, n))
            lab = sum(pick(r) in r["labels"] for r in structured)
            kept = sum(pick(r) == "noise" for r in stochastic)
            print(f"levels {levels} {pool}: labelled {lab}/{len(structured)}, stochastic keep noise "
                  f"{kept}/{len(stochastic)}; structured chose {dict(Counter(pick(r) for r in structured).most_common(4))}")
        fam = sum(min(fams(r)[:3], key=lambda n: dist(r, n)) in r["labels"] for r in structured)
        print(f"levels {levels} among the three fitted families alone: labelled {fam}/{len(structured)}")


if __name__ == "__main__":
    main()
