#!/usr/bin/env python3
"""Mitsuba's documentation gallery against lumis (issue 37 item 5, first step: an offline table,
not yet a CI test). For every scene of ../shared/corpus/mitsuba-data/docs/scenes:

* lumis opens the unmodified XML (`lumis render --resolution-scale F`), or says why not;
* where it opens, K independent lumis renders (seeds 1..K, --spp N, MIS unless --strategy) and
  K independent Mitsuba 3.9.1 renders (llvm_ad_rgb, seeds 1..K, N spp) of the same XML at the
  same reduced film size (the film's width and height set in Mitsuba's parsed scene, each side
  rounded as lumis rounds it; nothing else changed, so the field of view and the filter are the
  scene's), compared per 8x8 block and channel by Welch's t-test on the K block means of each
  side (the variance *between* renders, so heavy tails count as they are, where a render's own
  sample variance would understate them; Student's t, not the normal, since K is small),
  Sidak-corrected family-wise alpha = 0.01 over the blocks and channels.

    pip install mitsuba==3.9.1; apt-get install libllvm19
    DRJIT_LIBLLVM_PATH=/usr/lib/x86_64-linux-gnu/libLLVM-19.so python3 tools/corpus.py \
        [--scale 0.125] [--spp 32] [--renders 8] [--strategy mis] [SCENE.xml ...]

prints one Markdown row per scene (docs/mitsuba.md keeps the last table with its date).
"""

import argparse
import math
import os
import re
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


def block_means(images):
    """Per 8x8 block and channel, the block's mean in each of the K images."""
    h, w = len(images[0]), len(images[0][0])
    out = []
    for by in range(0, h, BLOCK):
        for bx in range(0, w, BLOCK):
            pix = [(y, x) for y in range(by, min(by + BLOCK, h)) for x in range(bx, min(bx + BLOCK, w))]
            for c in range(3):
                out.append([sum(img[y][x][c] for y, x in pix) / len(pix) for img in images])
    return out


def betacf(a, b, x):
    """The continued fraction of the regularized incomplete beta (Lentz's method)."""
    tiny, qab, qap, qam = 1e-300, a + b, a + 1.0, a - 1.0
    c, d = 1.0, 1.0 - qab * x / qap
    d = 1.0 / (d if abs(d) > tiny else tiny)
    h = d
    for m in range(1, 400):
        m2 = 2 * m
        for aa in (m * (b - m) * x / ((qam + m2) * (a + m2)),
                   -(a + m) * (qab + m) * x / ((a + m2) * (qap + m2))):
            d = 1.0 + aa * d
            d = 1.0 / (d if abs(d) > tiny else tiny)
            c = 1.0 + aa / c
            c = c if abs(c) > tiny else tiny
            h *= d * c
        if abs(d * c - 1.0) < 1e-14:
            break
    return h


def betai(a, b, x):
    """The regularized incomplete beta function I_x(a, b)."""
    if x <= 0.0:
        return 0.0
    if x >= 1.0:
        return 1.0
    lbt = math.lgamma(a + b) - math.lgamma(a) - math.lgamma(b) + a * math.log(x) + b * math.log(1 - x)
    if x < (a + 1) / (a + b + 2):
        return math.exp(lbt) * betacf(a, b, x) / a
    return 1.0 - math.exp(lbt) * betacf(b, a, 1 - x) / b


def t_two_sided_p(t, dof):
    """P(|T| >= |t|) for Student's t with `dof` degrees of freedom."""
    return betai(dof / 2.0, 0.5, dof / (dof + t * t))


def block_test(ours, theirs):
    """Welch's t-test per block and channel on the K block means of each side (the variance
    between renders, so heavy tails are seen as they are), Sidak over all; returns (failed,
    comparisons, worst |t|, smallest p, per-comparison alpha)."""
    a, b = block_means(ours), block_means(theirs)
    ka, kb = len(ours), len(theirs)
    tests = []
    for xa, xb in zip(a, b):
        ma, mb = sum(xa) / ka, sum(xb) / kb
        va = sum((v - ma) ** 2 for v in xa) / (ka - 1) / ka
        vb = sum((v - mb) ** 2 for v in xb) / (kb - 1) / kb
        if va + vb <= 0:
            same = abs(ma - mb) <= 1e-6 * max(abs(ma), abs(mb), 1e-6)
            tests.append((0.0 if same else math.inf, 1.0 if same else 0.0))
            continue
        t = (ma - mb) / math.sqrt(va + vb)
        dof = (va + vb) ** 2 / (va * va / (ka - 1) + vb * vb / (kb - 1))
        tests.append((t, t_two_sided_p(t, dof)))
    alpha = 1 - (1 - ALPHA) ** (1 / len(tests))
    failed = sum(1 for _, p in tests if p < alpha)
    if os.environ.get("CORPUS_VERBOSE"):
        for i, (t, p) in enumerate(tests):
            if p < alpha:
                sys.stderr.write(f"  comparison {i} (block {i // 3}, ch {i % 3}): t {t:.2f}, p {p:.2e}\n")
    return failed, len(tests), max(abs(t) for t, _ in tests), min(p for _, p in tests), alpha


def image_mean(images):
    """The mean over the K images and their pixels, per channel."""
    n = len(images) * len(images[0]) * len(images[0][0])
    return [sum(p[c] for img in images for row in img for p in row) / n for c in range(3)]


def load_resized(mi, path, scale, spp):
    """Mitsuba's scene of the unmodified XML `path` with its film's width and height scaled by
    `scale` (each rounded as lumis rounds it) in the parsed scene, nothing else changed; `$spp`
    set to `spp` where the scene needs it. Also used by tools/make_gallery_reference.py."""
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
    # Files named relative to the scene or to its <path>s (an included file's meshes, e.g.
    # integrator_direct_*.xml's veach_mis.xml) resolve at instantiation, which parse_file's
    # resolver no longer covers; mi.load_file keeps it for both.
    saved = mi.FileResolver(mi.file_resolver())
    resolver = mi.file_resolver()
    for value in reversed(re.findall(r'<path\s+value="([^"]+)"', path.read_text())):
        resolver.prepend(str((path.parent / value).resolve()))
    resolver.prepend(str(path.parent))
    try:
        scene = mi.parser.instantiate(cfg, state)
    finally:
        mi.set_file_resolver(saved)
    return scene


def mitsuba_renders(mi, path, scale, spp, k):
    scene = load_resized(mi, path, scale, spp)
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
    ap.add_argument("--scale", type=float, default=0.125)
    ap.add_argument("--spp", type=int, default=32)
    ap.add_argument("--renders", type=int, default=8)
    ap.add_argument("--strategy", default="mis")
    args = ap.parse_args()
    import mitsuba as mi
    mi.set_variant("llvm_ad_rgb")
    mi.set_log_level(mi.LogLevel.Error)
    scenes = [Path(s).resolve() for s in args.scenes] or sorted(GALLERY.glob("*.xml"))
    print("| scene | lumis | size | Mitsuba mean (RGB) | lumis − Mitsuba (rel.) | comparisons failed "
          "| worst |t| (smallest p, per-comparison α) | verdict |")
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
            failed, total, worst, p_min, alpha = block_test(ours, theirs)
            ma, mb = image_mean(ours), image_mean(theirs)
            rel = [(x - y) / y if y else 0.0 for x, y in zip(ma, mb)]
            size = f"{len(ours[0][0])}×{len(ours[0])}"
            verdict = "agrees" if failed == 0 else "DIFFERS"
            print(f"| {name} | opens | {size} | {' '.join('%.4g' % v for v in mb)} | "
                  f"{' '.join('%+.2f%%' % (100 * r) for r in rel)} | {failed}/{total} | "
                  f"{worst:.1f} (p {p_min:.1e}, α {alpha:.1e}) | {verdict} |", flush=True)
            sys.stderr.write(f"{name}: {time.time() - t:.0f} s\n")


if __name__ == "__main__":
    main()
