#!/usr/bin/env python3
"""Cross-validates two uses of the straight-line cues in the family choice, offline.

Input: the JSON lines of `proctex fidelity --set ../shared/photos/dev --json`, whose patches carry
their whole ranking, the source patch's cues (`photo_cues`) and every ranked candidate's render's
cues (`cues`), in the order of `proctex::cues::CUE_NAMES`; `straight_lines` is the strongest long
straight line in robust deviations of all lines, `crossing_lines` the strongest line across it as
a share of it (`proctex::straight_lines`).

- **rule**: where the photo's `straight_lines` is above a threshold, the first of a set of line
  families (lattices: brick, grid, planks; lines: those and wood lines) in the run's order comes
  first. (A wall, a boarded surface or a panel has long straight joints; the descriptor's
  energies, averaged over the patch, see mostly the grain between them.)
- **render**: the candidates that the product renders (the noise model and the
  `RENDER_ORDERED` families nearest by structure distance) are ordered again by their rank key plus
  `w1·|ln lines(photo) − ln lines(render)| + w2·|crossing(photo) − crossing(render)|`, the second
  term only where both have a line above 8 deviations (analysis by synthesis on a statistic the
  descriptor does not hold); the other candidates keep their places.

The rank key is the run's order itself (each candidate's score raised to the largest score before
it, so that w = 0 and "off" reproduce every recorded choice; the script checks that).

Protocol: 4 folds by devset::fold_of; on each held-out fold the parameters are chosen on the
other three: the most structured patches labelled among the values that keep >= 95 % of the
stochastic patches served (ties: the fewest patches moved, i.e. the smallest weight or the
highest threshold). A stochastic patch is served when the choice is the noise model, or the
family the run chose and measured no farther than the noise model. With --nested the use (rule
or render) and the rule's family set are chosen on the training folds too.

Usage: tools/devset_straight_lines_cv.py RUN.jsonl [--folds F] [--noise-after-best]
"""
import json
import math
import sys

from devset_occam_cv import fold_of, patch_overall, tally_orders

CUE_NAMES = ["lattice", "lattice2", "lobe_elongation", "coherence", "axis_alignment",
             "kurtosis", "kurtosis_fine", "skewness", "bimodality", "edge_sparsity",
             "straight_lines", "crossing_lines"]
LINES, CROSSING = CUE_NAMES.index("straight_lines"), CUE_NAMES.index("crossing_lines")
SETS = {"lattices": {"brick", "grid", "planks"},
        "lines": {"brick", "grid", "planks", "wood_lines"}}
W1 = [0, 0.1, 0.2, 0.3, 0.5, 0.75, 1.0, 1.5, 2.0, 3.0, 4.0]
W2 = [0, 0.5, 1.0, 2.0]
CROSSING_FLOOR = 8.0


def patches(photos):
    out = []
    for p in photos:
        e = p["entry"]
        for i, c in enumerate(p["choices"]):
            key, top = [], -math.inf
            for j, r in enumerate(c["ranking"]):
                top = max(top, r["score"])
                key.append(top + 1e-9 * j)
            out.append(dict(
                file=e["file"], category=e["category"], labels=e["families"] or [],
                chosen=c["chosen"], ranking=c["ranking"], key=key, photo=c["photo_cues"],
                family_ok=patch_overall(p["auto"], i) <= patch_overall(p["noise"], i)))
    return out


RENDER_ORDERED = 3  # retrieve::RENDER_ORDERED
TEXTURE_WEIGHT_PRODUCT = 0.9  # retrieve::TEXTURE_WEIGHT
SKEWNESS = CUE_NAMES.index("skewness")
DARK_NETWORK_SKEWNESS = -0.599  # retrieve::DARK_NETWORK_SKEWNESS
# Where the product puts the noise model on a dark network: after the fitted families (since
# 2026-11-30), or right after the best one (runs recorded before that: --noise-after-best).
NOISE_AFTER_FITTED = "--noise-after-best" not in sys.argv


def structure(r):
    return r["refined"] if r["refined"] is not None else r["retrieval"]


def rendered_names(ranking):
    """The noise model and the families that the product fits and renders: the first
    RENDER_ORDERED by structure distance."""
    families = sorted((r for r in ranking if r["name"] != "noise"), key=structure)
    return {"noise"} | {r["name"] for r in families[:RENDER_ORDERED]}


def line_term(pt, r, w1, w2):
    """How far candidate `r`'s render is from the photo in its straight lines."""
    lp, lr = max(pt["photo"][LINES], 1.0), max(r["cues"][LINES], 1.0)
    d = w1 * abs(math.log(lp) - math.log(lr))
    if min(lp, lr) > CROSSING_FLOOR:
        d += w2 * abs(pt["photo"][CROSSING] - r["cues"][CROSSING])
    return d


def order_render(pt, w1, w2):
    def extra(r):
        return line_term(pt, r, w1, w2)

    rk = pt["ranking"]
    shown = rendered_names(rk)
    slots = [j for j, r in enumerate(rk) if r["name"] in shown]
    moved = sorted(slots, key=lambda j: pt["key"][j] + extra(rk[j]))
    names = [r["name"] for r in rk]
    for slot, j in zip(slots, moved):
        names[slot] = rk[j]["name"]
    return names


def order_product(pt, w1, w2):
    """The product's ranking (retrieve::Suggester::ranked) computed again from the recorded
    distances, each fitted candidate's texture distance plus the straight-line term."""
    def extra(r):
        return line_term(pt, r, w1, w2)

    rk = pt["ranking"]
    noise = next(r for r in rk if r["name"] == "noise")
    families = sorted((r for r in rk if r["name"] != "noise"), key=structure)
    margin = families[-1]["score"] - structure(families[-1])
    head = []
    for r in families[:RENDER_ORDERED]:
        texture = r["distance"] + extra(r)
        head.append((TEXTURE_WEIGHT_PRODUCT * texture + (1 - TEXTURE_WEIGHT_PRODUCT) * structure(r)
                     + margin, texture, r["name"]))
    head.sort()
    best_score, best_texture, _ = head[0]
    if pt["photo"][SKEWNESS] < DARK_NETWORK_SKEWNESS:
        after = head[-1][0] if NOISE_AFTER_FITTED else best_score
        noise_score = math.nextafter(after, math.inf)
    else:
        noise_score = noise["distance"] + extra(noise) - (best_texture - best_score) - margin
    ranked = sorted(head + [(noise_score, 0.0, "noise")], key=lambda x: x[0])
    return [name for _, _, name in ranked] + [r["name"] for r in families[RENDER_ORDERED:]]


def order_rule(pt, family_set, threshold):
    names = [r["name"] for r in pt["ranking"]]
    if pt["photo"][LINES] > threshold:
        first = next((n for n in names if n in SETS[family_set]), None)
        if first is not None:
            names.remove(first)
            names.insert(0, first)
    return names


def order(pt, use):
    kind, a, b = use
    if kind == "render":
        return order_render(pt, a, b)
    if kind == "product":
        return order_product(pt, a, b)
    return order_rule(pt, a, b)


def tally(pts, use):
    return tally_orders(pts, lambda pt: order(pt, use))


def candidates(pts, kinds):
    out = []
    for kind in ("render", "product"):
        if kind in kinds:
            out += [(kind, a, b) for a in W1 for b in W2]
    for s in SETS:
        if s in kinds:
            values = sorted({pt["photo"][LINES] for pt in pts})
            out.append(("rule", s, math.inf))
            out += [("rule", s, (x + y) / 2) for x, y in zip(values, values[1:])]
    return out


def cost(use):
    """Smaller: fewer patches moved (ties go to it)."""
    kind, a, b = use
    return -b if kind == "rule" else a + b


def pick(pts, kinds):
    best = None
    for use in candidates(pts, kinds):
        lab, _, _, served, nt = tally(pts, use)
        if served < 0.95 * nt:
            continue
        if best is None or (lab, -cost(use)) > (best[0], -cost(best[1])):
            best = (lab, use)
    return best[1]


def fmt(use):
    kind, a, b = use
    return f"rule {a} > {b:.2f}" if kind == "rule" else f"{kind} w1={a} w2={b}"


def main():
    args = sys.argv[1:]
    folds = int(args[args.index("--folds") + 1]) if "--folds" in args else 4
    photos = [json.loads(l)["photo"] for l in open(args[0]) if '"photo"' in l]
    pts = patches(photos)
    agree = sum(order(pt, ("render", 0, 0))[0] == pt["chosen"] for pt in pts)
    same = sum(order(pt, ("product", 0, 0)) == [r["name"] for r in pt["ranking"]] for pt in pts)
    print(f"the product's ranking computed again: {same}/{len(pts)} orders as recorded")
    print(f"{len(photos)} photos, {len(pts)} patches; the rank key reproduces {agree}/{len(pts)} "
          "choices")
    lab, top3, ns, served, nt = tally(pts, ("render", 0, 0))
    print(f"as run: structured labelled {lab}/{ns}, top three {top3}, stochastic served "
          f"{served}/{nt}")
    print("whole set (for reading, not for choosing):")
    for kind in ("render", "product"):
        for w1 in W1:
            t = tally(pts, (kind, w1, 0))
            t2 = tally(pts, (kind, w1, 1.0))
            print(f"  {kind} w1={w1:4}: labelled {t[0]:3}, top three {t[1]:3}, served {t[3]:3}"
                  f"   (w2=1: {t2[0]:3}, {t2[1]:3}, {t2[3]:3})")
    for kinds in (["render"], ["product"], ["lattices"], ["lines"],
                  ["product", "lattices", "lines"]):
        total = [0] * 5
        lines = []
        for f in range(folds):
            train = [pt for pt in pts if fold_of(pt["file"], folds) != f]
            test = [pt for pt in pts if fold_of(pt["file"], folds) == f]
            use = pick(train, kinds)
            t = tally(test, use)
            total = [x + y for x, y in zip(total, t)]
            lines.append(f"fold {f}: {fmt(use)}: {t[0]}/{t[2]}")
        print(f"{' + '.join(kinds)}, held out: structured labelled {total[0]}/{total[2]}, top "
              f"three {total[1]}, stochastic served {total[3]}/{total[4]}")
        for line in lines:
            print("   ", line)


if __name__ == "__main__":
    main()
