#!/usr/bin/env python3
"""Builds the family-classifier laboratory's training corpus: downloads the Debian packages that
tools/corpus/labels*.tsv name (apt-get download; Debian's archive is one of the registries this
project's machines reach), and writes every labelled file into OUT under the name the labels use.
0 A.D.'s terrain textures are DXT-compressed DDS files: they are written as OUT/dds/*.dds and
decoded to PNG by `corpus_lab dds` (run after this script; the command is printed).

Names: 0ad-data `art/textures/terrain/types/a/b.png.cached.dds` -> `a__b.png`;
nexuiz-textures `textures/a/b.jpg` -> `a__b.jpg`; redeclipse-data and supertuxkart-data
`.../dir/file` -> `re__dir__file` and `stk__dir__file`; cube2-data and extremetuxracer-data
likewise, `cube2__dir__file` and `etr__dir__file`; ufoai-textures `textures/a/b.png` (in its
0textures.pk3) -> `ufo__a__b.png`.

Usage: tools/corpus/extract.py OUT [--cache DIR] [--also LABELS]...   (the packages are about 3.5 GB
together; with not_kept/labels4.tsv 3.8 GB). `--also` adds a label file that the product's table
is not trained on (`not_kept/`: batches measured and not kept, docs/devset.md).
"""
import os
import subprocess
import sys
import tempfile
import zipfile

HERE = os.path.dirname(os.path.abspath(__file__))

# Packages whose files are named `tag__dir__file` (`from_tree`).
TREE_TAGS = {
    "redeclipse-data": "re",
    "supertuxkart-data": "stk",
    "cube2-data": "cube2",
    "extremetuxracer-data": "etr",
}


def labelled(also=()):
    """The labelled files of every labels*.tsv here and of the label files `also`, by package."""
    by_package = {}
    here = sorted(os.path.join(HERE, f) for f in os.listdir(HERE)
                  if f.startswith("labels") and f.endswith(".tsv"))
    for labels in here + list(also):
        for line in open(labels):
            if line.startswith("#") or not line.strip():
                continue
            name, _family, package = line.rstrip("\n").split("\t")
            by_package.setdefault(package, set()).add(name)
    return by_package


def download(package, cache):
    for f in os.listdir(cache):
        if f.startswith(package + "_") and f.endswith(".deb"):
            return os.path.join(cache, f)
    subprocess.run(["apt-get", "download", package], cwd=cache, check=True,
                   stdout=subprocess.DEVNULL)
    return download(package, cache)


def extract_member(deb, member, into):
    """One file of a .deb's data archive, extracted under `into`; its path there."""
    tar = subprocess.Popen(["dpkg-deb", "--fsys-tarfile", deb], stdout=subprocess.PIPE)
    subprocess.run(["tar", "-x", "-C", into, "." + member], stdin=tar.stdout, check=True)
    tar.wait()
    return os.path.join(into, member.lstrip("/"))


def from_zip(path, prefix, rename, wanted, out):
    found = 0
    with zipfile.ZipFile(path) as z:
        for n in z.namelist():
            if not n.startswith(prefix):
                continue
            flat = rename(n[len(prefix):].replace("/", "__"))
            if flat in wanted:
                with open(os.path.join(out, flat), "wb") as f:
                    f.write(z.read(n))
                found += 1
    return found


def from_tree(deb, tag, wanted, out):
    found = 0
    with tempfile.TemporaryDirectory() as tmp:
        subprocess.run(["dpkg-deb", "-x", deb, tmp], check=True)
        for d, _, files in os.walk(tmp):
            for f in files:
                flat = f"{tag}__{os.path.basename(d)}__{f}"
                if flat in wanted:
                    with open(os.path.join(d, f), "rb") as src, \
                            open(os.path.join(out, flat), "wb") as dst:
                        dst.write(src.read())
                    found += 1
    return found


def main():
    args = sys.argv[1:]
    out = os.path.abspath(args[0])
    cache = os.path.abspath(args[args.index("--cache") + 1]) if "--cache" in args else out + "-debs"
    also = [args[i + 1] for i, a in enumerate(args) if a == "--also"]
    os.makedirs(os.path.join(out, "dds"), exist_ok=True)
    os.makedirs(cache, exist_ok=True)
    for package, wanted in sorted(labelled(also).items()):
        deb = download(package, cache)
        with tempfile.TemporaryDirectory() as tmp:
            if package == "0ad-data":
                z = extract_member(deb, "/usr/share/games/0ad/mods/public/public.zip", tmp)
                # Decoded names drop the ".dds.cached.dds" or ".png.cached.dds" and end ".png".
                stems = {w[: -len(".png")] for w in wanted}

                def dds_name(flat):
                    for ending in (".dds.cached.dds", ".png.cached.dds"):
                        if flat.endswith(ending) and flat[: -len(ending)] in stems:
                            return flat[: -len(ending)] + ".dds"
                    return None

                found = from_zip(z, "art/textures/terrain/types/", dds_name,
                                 {s + ".dds" for s in stems}, os.path.join(out, "dds"))
            elif package == "nexuiz-textures":
                z = extract_member(deb, "/usr/share/games/nexuiz/data/textures.pk3", tmp)
                found = from_zip(z, "textures/", lambda flat: flat, wanted, out)
            elif package == "ufoai-textures":
                z = extract_member(deb, "/usr/share/games/ufoai/base/0textures.pk3", tmp)
                found = from_zip(z, "textures/", lambda flat: "ufo__" + flat, wanted, out)
            else:
                tag = TREE_TAGS[package]
                found = from_tree(deb, tag, wanted, out)
        print(f"{package}: {found} of {len(wanted)} labelled files")
    print(f"then: cargo run --release -p proctex-analyzer --example corpus_lab -- dds "
          f"{os.path.join(out, 'dds')} {out}")
    print(f"and, to train the product's family classifier again on every labels*.tsv: "
          f"cat tools/corpus/labels*.tsv > /tmp/labels_all.tsv; cargo run --release -p "
          f"proctex-analyzer --example corpus_lab -- table /tmp/labels_all.tsv {out} "
          f"analyzer/src/family_classifier_table.rs")


if __name__ == "__main__":
    main()
