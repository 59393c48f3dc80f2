#!/usr/bin/env python3
"""The Mitsuba 3.9.1 reference of one gallery scene at a reduced film size, for
renderer/tests/gallery.rs (issue 37 item 5): the unmodified XML parsed by Mitsuba, its film's
width and height set to round(side * SCALE) (lumis' `--resolution-scale` rounding, half away from
zero; nothing else changed, so the field of view and the filter are the scene's, as
tools/corpus.py does), rendered as two independent halves A and B (llvm_ad_rgb; each the average
of SPP/PASS single-pass renders of PASS spp with seeds SEED*100003 + i), written as
OUT.exr = (A + B)/2 and OUT.var.exr = (A - B)^2/4 per pixel and channel. Prints the render time,
the relMSE of the reference's own noise and the largest relative sd of an 8x8 block mean.

    DRJIT_LIBLLVM_PATH=/usr/lib/x86_64-linux-gnu/libLLVM-19.so python3 \\
        tools/make_gallery_reference.py SCENE.xml OUT [--scale 0.125] [--spp 16384] \\
        [--pass 1024] [--seed-a 1] [--seed-b 2]

Tests never run it; tests/data/refs/README.md records each reference's command.
"""

import argparse
import sys
import time
from pathlib import Path

import numpy as np
import mitsuba as mi


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("scene")
    ap.add_argument("out")
    ap.add_argument("--scale", type=float, default=0.125)
    ap.add_argument("--spp", type=int, default=16384)
    ap.add_argument("--pass", dest="npass", type=int, default=1024)
    ap.add_argument("--seed-a", type=int, default=1)
    ap.add_argument("--seed-b", type=int, default=2)
    a = ap.parse_args()
    assert a.spp % a.npass == 0, "--spp must be a multiple of --pass"
    mi.set_variant("llvm_ad_rgb")
    # The same parsed, resized scene as tools/corpus.py's Mitsuba side.
    sys.path.insert(0, str(Path(__file__).resolve().parent))
    from corpus import load_resized

    scene = load_resized(mi, Path(a.scene).resolve(), a.scale, a.spp)
    film = scene.sensors()[0].film().size()
    print("film %dx%d" % (film[0], film[1]))

    def half(seed):
        acc = None
        for i in range(a.spp // a.npass):
            img = np.array(mi.render(scene, seed=seed * 100003 + i, spp=a.npass), dtype=np.float64)[..., :3]
            acc = img if acc is None else acc + img
        return acc / (a.spp // a.npass)

    t = time.time()
    ha, hb = half(a.seed_a), half(a.seed_b)
    print("render time %.0f s" % (time.time() - t))
    mean, var = (ha + hb) / 2, (ha - hb) ** 2 / 4
    for suffix, x in ((".exr", mean), (".var.exr", var)):
        mi.Bitmap(x.astype(np.float32), mi.Bitmap.PixelFormat.RGB).write(a.out + suffix)
    print("relMSE of the reference's own noise: %.3g" % np.mean(var / (mean ** 2 + 1e-2)))
    print("mean rgb", mean.reshape(-1, 3).mean(0), "non-finite", int((~np.isfinite(mean)).sum()))
    h, w = mean.shape[:2]
    worst = 0.0
    for y in range(0, h, 8):
        for x in range(0, w, 8):
            m = mean[y:y + 8, x:x + 8].reshape(-1, 3)
            v = var[y:y + 8, x:x + 8].reshape(-1, 3)
            worst = max(worst, float((np.sqrt(v.sum(0)) / len(m) / np.maximum(m.mean(0), 1e-6)).max()))
    print("largest relative sd of an 8x8 block mean: %.2g" % worst)


if __name__ == "__main__":
    main()
