#!/usr/bin/env python3
"""Chooses among variants of the product, each measured by its own run of the yardstick, by
cross-validation over the development set's photos.

Input: one `proctex fidelity --set ../shared/photos/dev --json` run per variant (NAME=RUN; the
first is the product as it is, which wins ties). Protocol: 4 folds by devset::fold_of (FNV-1a of
the file name); for each held-out fold, the variant with the most chosen renders within the
speck limit (1.5× the photo's own fraction, `devset::speck_ratio`) on the other three folds,
ties by more structured patches labelled there, then the order given; its held-out fold's counts
are summed. Prints the folds' choices, the held-out totals and each variant's whole-set counts.

With `--every-render`, the first criterion is every fitted candidate's render within the speck
limit instead (each patch's ranking: the noise model and the families the ranking fitted), for a
change to how a family is drawn, which shows in its renders whether or not it is chosen.

Usage: tools/devset_variant_cv.py [--every-render] NAME=RUN.jsonl NAME=RUN.jsonl ...
"""
import json
import sys

from devset_occam_cv import fold_of, patch_overall

FOLDS = 4
SPECK_LIMIT = 1.5


def counts(path):
    """Per fold: speck-clean renders, structured labelled, labelled in the top three, stochastic
    served (the noise model, or a family whose overall ratio is no worse)."""
    c = {k: [0] * FOLDS for k in ("speck", "every", "labelled", "top3", "served")}
    for line in open(path):
        if not line.startswith('{"photo"'):
            continue
        p = json.loads(line)["photo"]
        e = p["entry"]
        f = fold_of(e["file"], FOLDS)
        for i, ch in enumerate(p["choices"]):
            floor = 1.0 / ch["pixels"]
            ratio = (ch["render_specks"] + floor) / (ch["photo_specks"] + floor)
            c["speck"][f] += ratio <= SPECK_LIMIT
            c["every"][f] += sum(
                (r["specks"] + floor) / (ch["photo_specks"] + floor) <= SPECK_LIMIT
                for r in ch["ranking"] if r.get("specks") is not None)
            if e["category"] == "structured":
                c["labelled"][f] += ch["chosen"] in e["families"]
                c["top3"][f] += any(t in e["families"] for t in ch["top3"])
            else:
                c["served"][f] += ch["chosen"] == "noise" or (
                    patch_overall(p["auto"], i) <= patch_overall(p["noise"], i))
    return c


def main():
    args = sys.argv[1:]
    first = "speck"
    if args[:1] == ["--every-render"]:
        first, args = "every", args[1:]
    variants = [(a.split("=", 1)[0], counts(a.split("=", 1)[1])) for a in args]
    if not variants:
        sys.exit(__doc__)
    held = {k: 0 for k in ("speck", "every", "labelled", "top3", "served")}
    chosen = []
    for fold in range(FOLDS):
        def train(v, k):
            return sum(v[1][k][g] for g in range(FOLDS) if g != fold)
        best = max(range(len(variants)),
                   key=lambda i: (train(variants[i], first), train(variants[i], "labelled"), -i))
        chosen.append(variants[best][0])
        for k in held:
            held[k] += variants[best][1][k][fold]
    print("folds chose:", ", ".join(chosen))
    print("held out: speck-clean {speck}, every render speck-clean {every}, labelled {labelled}, "
          "top three {top3}, served {served}".format(**held))
    for name, c in variants:
        print(f"  {name}: whole set speck-clean {sum(c['speck'])} (folds {c['speck']}), "
              f"every render {sum(c['every'])} (folds {c['every']}), "
              f"labelled {sum(c['labelled'])}, top three {sum(c['top3'])}, "
              f"served {sum(c['served'])}")


if __name__ == "__main__":
    main()
