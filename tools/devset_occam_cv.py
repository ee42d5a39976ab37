#!/usr/bin/env python3
"""Cross-validates the ranking's noise-model margin (`retrieve::NOISE_MODEL_MARGIN`, called OCCAM
until 2026-11-27) on the development set, offline.

Input: the JSON lines of `proctex fidelity --set ../shared/photos/dev --json` (one line per
photo, then the summary), whose patches carry their whole ranking. The ranking is a function
of those numbers (retrieve::Suggester::suggestions): the families are ordered by structure
distance, and the noise model comes first exactly when its texture distance is below the best
family's plus the margin, OCCAM × the patch's self-distance. So the choice under another OCCAM
needs no new analysis: margin' = margin × OCCAM' / OCCAM.

Protocol: F folds by devset::fold_of (FNV-1a of the file name); for each held-out fold, OCCAM
is chosen on the other folds (the largest structured labelled rate among the values that
serve ≥ 90 % of the stochastic patches; the best sum of both rates if none does) and scored
on the held-out fold. A stochastic patch counts as served when the choice is the noise model,
or the family measured for it and no farther than the noise model (a family the run did not
choose has no measured fidelity: not served, conservatively).

Usage: tools/devset_occam_cv.py RUN.jsonl [--folds F] [--current 0.2]
"""
import json
import sys

OCCAM_GRID = [round(0.05 * i, 2) for i in range(0, 41)]  # 0 .. 2


def quadrants(run):
    """(photo, index, choice) for every patch of a `proctex fidelity --json` run, in order."""
    for line in open(run):
        if not line.startswith('{"photo"'):
            continue
        p = json.loads(line)["photo"]
        for i, c in enumerate(p["choices"]):
            yield p, i, c


def noise_and_best(c):
    """A patch's noise-model entry and its best-scored fitted family."""
    noise = next(x for x in c["ranking"] if x["name"] == "noise")
    fitted = [x for x in c["ranking"] if x["name"] != "noise" and x.get("distance") is not None]
    return noise, min(fitted, key=lambda x: x["score"])


def fold_of(name, folds):
    h = 0xcbf29ce484222325
    for b in name.encode():
        h = ((h ^ b) * 0x100000001b3) & 0xFFFFFFFFFFFFFFFF
    return h % folds


def patch_overall(fid, i):
    d, h = fid["per_patch"][i], fid["halves"]
    return (d["spectrum_db"] / max(h["spectrum_db"], 1e-9) + d["colour"] / max(h["colour"], 1e-9)
            + d["structure"] / max(h["structure"], 1e-9)) / 3


def tally_orders(pts, order_of):
    """Labelled first and top three of the structured patches, served stochastic ones, for the
    orders `order_of(pt)` gives (names, first first). A stochastic patch is served when the noise
    model is first, or the family the run chose and measured no farther than the noise model
    (pt["chosen"], pt["family_ok"]). Returns (labelled, top3, structured, served, stochastic)."""
    lab = top3 = served = ns = nt = 0
    for pt in pts:
        o = order_of(pt)
        if pt["category"] == "structured":
            ns += 1
            lab += o[0] in pt["labels"]
            top3 += any(n in pt["labels"] for n in o[:3])
        else:
            nt += 1
            served += o[0] == "noise" or (o[0] == pt["chosen"] and (
                pt["chosen"] == "noise" or pt["family_ok"]))
    return lab, top3, ns, served, nt


def ranking_rows(photos):
    """Every patch of a run's photos: (photo, patch index, its choice, the noise model's
    ranking row, the families' rows)."""
    for p in photos:
        for i, c in enumerate(p["choices"]):
            rank = c["ranking"]
            noise = next(r for r in rank if r["name"] == "noise")
            yield p, i, c, noise, [r for r in rank if r["name"] != "noise"]


def ranking_margin(fams):
    """The margin a ranking's families were scored with: the family farthest by structure scores
    its structure distance plus the margin, whichever order ranked the list (the nearest ones may
    be reordered by a blend)."""
    structure = [r["refined"] if r["refined"] is not None else r["retrieval"] for r in fams]
    far = max(range(len(fams)), key=lambda j: structure[j])
    return fams[far]["score"] - structure[far]


def patches(photos, current):
    """(photo file, category, labels, the families' ranking rows, per-occam chooser,
    served-if-family) per patch."""
    out = []
    for p, i, c, noise, fams in ranking_rows(photos):
        e = p["entry"]
        best = min(fams, key=lambda r: r["score"])
        margin = ranking_margin(fams)
        family_ok = (c["chosen"] == best["name"]
                     and patch_overall(p["auto"], i) <= patch_overall(p["noise"], i))
        out.append(dict(file=e["file"], category=e["category"], labels=e["families"] or [],
                        families=fams,
                        noise_d=noise["distance"], best=best["name"], best_d=best["distance"],
                        self_d=margin / current, chosen=c["chosen"], family_ok=family_ok))
    return out


def choose(pt, occam):
    return "noise" if pt["noise_d"] < pt["best_d"] + occam * pt["self_d"] else pt["best"]


def rates(pts, occam):
    s = [pt for pt in pts if pt["category"] == "structured"]
    t = [pt for pt in pts if pt["category"] == "stochastic"]
    lab = sum(choose(pt, occam) in pt["labels"] for pt in s) / max(len(s), 1)
    served = sum(1 for pt in t if (c := choose(pt, occam)) == "noise"
                 or (c == pt["best"] and pt["family_ok"])) / max(len(t), 1)
    return lab, served


def pick(pts):
    scored = [(occam, *rates(pts, occam)) for occam in OCCAM_GRID]
    ok = [x for x in scored if x[2] >= 0.9]
    if ok:
        return max(ok, key=lambda x: (x[1], x[2]))[0]
    return max(scored, key=lambda x: x[1] + x[2])[0]


def main():
    args = sys.argv[1:]
    folds, current = 4, 0.2
    if "--folds" in args:
        folds = int(args[args.index("--folds") + 1])
    if "--current" in args:
        current = float(args[args.index("--current") + 1])
    photos = [json.loads(l)["photo"] for l in open(args[0]) if '"photo"' in l]
    pts = patches(photos, current)
    lab, served = rates(pts, current)
    # The current choice must come out of the ranking's numbers as the run made it.
    agree = sum(choose(pt, current) == pt["chosen"] for pt in pts)
    print(f"{len(photos)} photos, {len(pts)} patches; the numbers reproduce {agree}/{len(pts)} "
          f"choices at OCCAM {current}")
    print(f"OCCAM {current} (current): structured labelled {lab:.1%}, stochastic served {served:.1%}")
    s_pts = [pt for pt in pts if pt["category"] == "structured"]
    bound = sum(pt["best"] in pt["labels"] for pt in s_pts) / max(len(s_pts), 1)
    print(f"structured patches whose best family (by structure distance) is labelled: {bound:.1%} "
          "(the most any OCCAM can reach)")
    print("whole set, every OCCAM of the grid (for reading, not for choosing):")
    for occam in OCCAM_GRID[::4]:
        l, s = rates(pts, occam)
        print(f"  OCCAM {occam:4.2f}: structured labelled {l:6.1%}, stochastic served {s:6.1%}")
    # Every patch judged once, with the OCCAM chosen without its photo's fold.
    pooled = []
    for k in range(folds):
        train = [pt for pt in pts if fold_of(pt["file"], folds) != k]
        test = [pt for pt in pts if fold_of(pt["file"], folds) == k]
        if not test:
            continue
        occam = pick(train)
        l, s = rates(test, occam)
        n = len({pt["file"] for pt in test})
        pooled += [dict(pt, held_out_occam=occam) for pt in test]
        print(f"fold {k} held out ({n} photos): OCCAM chosen on the others {occam:.2f}; "
              f"held-out structured labelled {l:.1%}, stochastic served {s:.1%}")
    s = [pt for pt in pooled if pt["category"] == "structured"]
    t = [pt for pt in pooled if pt["category"] == "stochastic"]
    lab = sum(choose(pt, pt["held_out_occam"]) in pt["labels"] for pt in s)
    served = sum(1 for pt in t if (c := choose(pt, pt["held_out_occam"])) == "noise"
                 or (c == pt["best"] and pt["family_ok"]))
    print(f"held-out folds pooled: structured labelled {lab}/{len(s)} = {lab / max(len(s), 1):.1%}, "
          f"stochastic served {served}/{len(t)} = {served / max(len(t), 1):.1%}")


if __name__ == "__main__":
    main()
