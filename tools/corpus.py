#!/usr/bin/env python3
"""Mitsuba's documentation gallery against lumis (issue 37 item 5, first step: an offline table,
not yet a CI test). For every scene of ../shared/corpus/mitsuba-data/docs/scenes:

* lumis opens the unmodified XML (`lumis render --resolution-scale F`), or says why not;
* where it opens, K independent lumis renders (seeds 1..K, --spp N, MIS unless --strategy) and
  K independent Mitsuba 3.9.1 renders (llvm_ad_rgb, seeds 1..K, N spp) of the same XML at the
  same reduced film size (the film's width and height set in Mitsuba's parsed scene, each side
  rounded as lumis rounds it; nothing else changed, so the field of view and the filter are the
  scene's), and their means compared per 8x8 block and channel:
  z = (mean_lumis - mean_mitsuba) / sqrt(v_lumis + v_mitsuba), each v the block mean's variance
  estimated from the spread *between* the K renders (robust to heavy tails, where a render's own
  sample variance is not), Sidak-corrected family-wise alpha = 0.01 over the blocks and channels.

    pip install mitsuba==3.9.1; apt-get install libllvm19
    DRJIT_LIBLLVM_PATH=/usr/lib/x86_64-linux-gnu/libLLVM-19.so python3 tools/corpus.py \
        [--scale 0.25] [--spp 64] [--renders 4] [--strategy mis] [SCENE.xml ...]

prints one Markdown row per scene (docs/mitsuba.md keeps the last table with its date).
"""

import argparse
import math
import os
import struct
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
GALLERY = ROOT.parent / "shared" / "corpus" / "mitsuba-data" / "docs" / "scenes"
LUMIS = ROOT / "target" / "release" / "lumis"
BLOCK = 8
ALPHA = 0.01


def lumis_side(n, scale):
    """lumis' `--resolution-scale` rounding (app/src/image_size.rs): half away from zero."""
    return max(1, math.floor(n * scale + 0.5))


def read_pfm(path):
    """A PFM (bottom row first) as rows top to bottom of [r, g, b] pixels."""
    data = path.read_bytes()
    parts = data.split(b"\n", 3)
    w, h = map(int, parts[1].split())
    scale = float(parts[2])
    fmt = "<" if scale < 0 else ">"
    floats = struct.unpack(fmt + "%df" % (w * h * 3), parts[3][: w * h * 12])
    rows = [[floats[(y * w + x) * 3:(y * w + x) * 3 + 3] for x in range(w)] for y in range(h)]
    return rows[::-1]


def mean_and_var(images):
    """Per pixel and channel: the mean of K images and the variance of that mean (between
    images)."""
    k = len(images)
    h, w = len(images[0]), len(images[0][0])
    mean = [[[0.0] * 3 for _ in range(w)] for _ in range(h)]
    var = [[[0.0] * 3 for _ in range(w)] for _ in range(h)]
    for y in range(h):
        for x in range(w):
            for c in range(3):
                vals = [img[y][x][c] for img in images]
                m = sum(vals) / k
                mean[y][x][c] = m
                var[y][x][c] = sum((v - m) ** 2 for v in vals) / (k - 1) / k
    return mean, var


def normal_critical(alpha):
    """Two-sided critical |z| for alpha, by bisection on erfc."""
    lo, hi = 0.0, 40.0
    for _ in range(200):
        mid = (lo + hi) / 2
        if math.erfc(mid / math.sqrt(2)) > alpha:
            lo = mid
        else:
            hi = mid
    return hi


def block_test(a, b):
    """(failed blocks, comparisons, worst |z|, critical) of two (mean, var) images."""
    (ma, va), (mb, vb) = a, b
    h, w = len(ma), len(ma[0])
    zs = []
    for by in range(0, h, BLOCK):
        for bx in range(0, w, BLOCK):
            pix = [(y, x) for y in range(by, min(by + BLOCK, h)) for x in range(bx, min(bx + BLOCK, w))]
            n = len(pix)
            for c in range(3):
                da = sum(ma[y][x][c] for y, x in pix) / n
                db = sum(mb[y][x][c] for y, x in pix) / n
                v = (sum(va[y][x][c] for y, x in pix) + sum(vb[y][x][c] for y, x in pix)) / n ** 2
                if v > 0:
                    zs.append((da - db) / math.sqrt(v))
                else:
                    zs.append(0.0 if abs(da - db) <= 1e-6 * max(abs(da), abs(db), 1e-6) else math.inf)
    critical = normal_critical(1 - (1 - ALPHA) ** (1 / len(zs)))
    failed = sum(1 for z in zs if abs(z) > critical)
    if os.environ.get("CORPUS_VERBOSE"):
        nx = (w + BLOCK - 1) // BLOCK
        for i, z in enumerate(zs):
            if abs(z) > critical:
                blk, c = divmod(i, 3)
                sys.stderr.write(f"  block ({BLOCK * (blk % nx)}, {BLOCK * (blk // nx)}) ch {c}: z {z:.2f}\n")
    return failed, len(zs), max(abs(z) for z in zs), critical


def image_mean(m):
    return [sum(p[c] for row in m for p in row) / (len(m) * len(m[0])) for c in range(3)]


def mitsuba_renders(mi, path, scale, spp, k):
    cfg = mi.parser.ParserConfig("llvm_ad_rgb")
    try:
        state = mi.parser.parse_file(cfg, str(path))
    except Exception as e:  # a scene that needs $spp gets it, as the gallery's own renders did
        if "spp" not in str(e):
            raise
        state = mi.parser.parse_file(cfg, str(path), spp=str(spp))
    size = None
    for node in state.nodes:
        if node.type == mi.ObjectType.Film:
            w, h = node.props["width"], node.props["height"]
            size = (lumis_side(w, scale), lumis_side(h, scale))
            node.props["width"], node.props["height"] = size
            break
    mi.parser.transform_all(cfg, state)
    scene = mi.parser.instantiate(cfg, state)
    images = []
    for seed in range(1, k + 1):
        img = mi.render(scene, seed=seed, spp=spp)
        h, w = img.shape[0], img.shape[1]
        flat = list(img.array)
        ch = img.shape[2]
        images.append([[flat[(y * w + x) * ch:(y * w + x) * ch + 3] for x in range(w)] for y in range(h)])
    return images


def lumis_renders(path, scale, spp, k, strategy, tmp):
    images = []
    for seed in range(1, k + 1):
        out = Path(tmp) / f"{path.stem}_{seed}.pfm"
        cmd = [str(LUMIS), "render", str(path), "--resolution-scale", str(scale), "--spp",
               str(spp), "--seed", str(seed), "--strategy", strategy, "-o", str(out)]
        r = subprocess.run(cmd, capture_output=True, text=True, cwd=path.parent)
        if r.returncode != 0:
            first = r.stderr.strip().splitlines()[-1] if r.stderr.strip() else "failed"
            return None, first
        images.append(read_pfm(out))
    return images, None


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("scenes", nargs="*")
    ap.add_argument("--scale", type=float, default=0.25)
    ap.add_argument("--spp", type=int, default=64)
    ap.add_argument("--renders", type=int, default=4)
    ap.add_argument("--strategy", default="mis")
    args = ap.parse_args()
    import mitsuba as mi
    mi.set_variant("llvm_ad_rgb")
    mi.set_log_level(mi.LogLevel.Error)
    scenes = [Path(s).resolve() for s in args.scenes] or sorted(GALLERY.glob("*.xml"))
    print(f"| scene | lumis | size | Mitsuba mean (RGB) | lumis − Mitsuba (rel.) | blocks failed | worst z | verdict |")
    print("|---|---|---|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as tmp:
        for path in scenes:
            name = path.name
            t = time.time()
            ours, why = lumis_renders(path, args.scale, args.spp, args.renders, args.strategy, tmp)
            if ours is None:
                print(f"| {name} | refused: {why.replace('|', '/')[:160]} | | | | | | |", flush=True)
                continue
            try:
                theirs = mitsuba_renders(mi, path, args.scale, args.spp, args.renders)
            except Exception as e:
                print(f"| {name} | opens | | Mitsuba cannot: {str(e).splitlines()[0][:100]} | | | | |", flush=True)
                continue
            a, b = mean_and_var(ours), mean_and_var(theirs)
            failed, total, worst, critical = block_test(a, b)
            ma, mb = image_mean(a[0]), image_mean(b[0])
            rel = [(x - y) / y if y else 0.0 for x, y in zip(ma, mb)]
            size = f"{len(a[0][0])}×{len(a[0])}"
            verdict = "agrees" if failed == 0 else "DIFFERS"
            print(f"| {name} | opens | {size} | {' '.join('%.4g' % v for v in mb)} | "
                  f"{' '.join('%+.2f%%' % (100 * r) for r in rel)} | {failed}/{total} | "
                  f"{worst:.1f} (crit {critical:.2f}) | {verdict} |", flush=True)
            sys.stderr.write(f"{name}: {time.time() - t:.0f} s\n")


if __name__ == "__main__":
    main()
