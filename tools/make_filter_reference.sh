#!/bin/sh
# Remakes the independent Mitsuba 3 reference of tests/data/mitsuba/gaussian_edges.xml (issue 18,
# the gaussian pixel filter):
#   tests/data/refs/gaussian_edges.exr      = (A + B) / 2
#   tests/data/refs/gaussian_edges.var.exr  = (A - B)^2 / 4   (per pixel and channel)
# where A and B are two independent renders (seeds 1811 and 1812) of SPP samples per pixel each,
# each the average of SPP/1024 single-pass renders of 1024 spp with pass seeds SEED*100003 + i,
# made by Mitsuba 3.9.1's llvm_ad_rgb variant from the XML file itself (mi.load_file), so with
# Mitsuba's default film filter (gaussian, stddev 0.5, radius 2, sample_border false). The llvm
# variant evaluates the filter exactly (`eval`); scalar_rgb would use its 31-bin table.
# Tests never run this; it needs a Python with mitsuba==3.9.1 (and Debian's libllvm19):
#   MITSUBA_PY=/path/to/venv/bin/python tools/make_filter_reference.sh
# Environment: MITSUBA_PY (default /tmp/mi/bin/python), SPP (default 131072), OUT (default
# tests/data/refs/gaussian_edges).
set -eu
cd "$(dirname "$0")/.."
PY=${MITSUBA_PY:-/tmp/mi/bin/python}
SPP=${SPP:-131072}
OUT=${OUT:-tests/data/refs/gaussian_edges}
nice "$PY" - tests/data/mitsuba/gaussian_edges.xml "$SPP" "$OUT" <<'PYEOF'
import sys, time
import numpy as np
import mitsuba as mi
mi.set_variant("llvm_ad_rgb")
xml, spp, out = sys.argv[1], int(sys.argv[2]), sys.argv[3]
PASS = 1024
scene = mi.load_file(xml, spp=PASS)

def half(seed):
    acc = None
    n = spp // PASS
    for i in range(n):
        img = np.array(mi.render(scene, seed=seed * 100003 + i, spp=PASS), dtype=np.float64)[..., :3]
        acc = img if acc is None else acc + img
    return acc / n

t = time.time()
a = half(1811)
b = half(1812)
print("render time %.0f s" % (time.time() - t))
mean, var = (a + b) / 2, (a - b) ** 2 / 4
def write(path, x):
    mi.Bitmap(x.astype(np.float32), mi.Bitmap.PixelFormat.RGB).write(path)
write(out + ".exr", mean)
write(out + ".var.exr", var)
print("relMSE of the reference's own noise: %.3g" % np.mean(var / (mean ** 2 + 1e-2)))
print("mean rgb", mean.reshape(-1, 3).mean(0), "non-finite", int((~np.isfinite(mean)).sum()))
h, w = mean.shape[:2]
worst = 0.0
for y in range(0, h, 16):
    for x in range(0, w, 16):
        m = mean[y:y + 16, x:x + 16].reshape(-1, 3)
        v = var[y:y + 16, x:x + 16].reshape(-1, 3)
        worst = max(worst, float((np.sqrt(v.sum(0)) / len(m) / m.mean(0)).max()))
print("largest relative sd of a 16x16 block mean: %.2g" % worst)
PYEOF
