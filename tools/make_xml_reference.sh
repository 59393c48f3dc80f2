#!/bin/sh
# Renders the independent Mitsuba 3 reference of one Mitsuba XML scene, from that very file
# (mi.load_file), as two independent halves A and B:
#   OUT.exr      = (A + B) / 2
#   OUT.var.exr  = (A - B)^2 / 4   (per pixel and channel: the variance of that mean)
# Each half is SPP samples per pixel, the average of SPP/PASS single-pass renders of PASS spp with
# pass seeds SEED*100003 + i (SEED = SEED_A for A, SEED_B for B), so the halves share no seed.
# Variant llvm_ad_rgb (Mitsuba 3.9.1; it evaluates the gaussian film filter exactly, scalar_rgb
# would use its 31-bin table). Tests never run this; it needs a Python with mitsuba==3.9.1 (and
# Debian's libllvm19).
#   tools/make_xml_reference.sh SCENE.xml OUT [NAME=VALUE ...]
# NAME=VALUE are passed to mi.load_file as parameters (the XML's <default>s); spp is not one of
# them (mi.render's spp overrides the sampler's sample_count).
# Environment: MITSUBA_PY (default /tmp/mi/bin/python), SPP (default 131072), PASS (default 1024;
# lower it for big images or deep paths: the LLVM variant keeps every lane of a pass in memory),
# SEED_A, SEED_B (default 1 and 2).
# It prints the render time, the relMSE of the reference's own noise (mean over pixels and
# channels of var / (mean^2 + 1e-2)) and the largest relative standard deviation of a 16x16 block
# mean, the numbers tests/data/refs/README.md records.
set -eu
if [ $# -lt 2 ]; then
    echo "usage: $0 SCENE.xml OUT [NAME=VALUE ...]" >&2
    exit 2
fi
PY=${MITSUBA_PY:-/tmp/mi/bin/python}
nice "$PY" - "$@" "${SPP:-131072}" "${PASS:-1024}" "${SEED_A:-1}" "${SEED_B:-2}" <<'PYEOF'
import sys, time
import numpy as np
import mitsuba as mi
mi.set_variant("llvm_ad_rgb")
xml, out = sys.argv[1], sys.argv[2]
params = dict(a.split("=", 1) for a in sys.argv[3:-4])
spp, npass, seed_a, seed_b = (int(x) for x in sys.argv[-4:])
assert spp % npass == 0, "SPP must be a multiple of PASS"
scene = mi.load_file(xml, **params)

def half(seed):
    acc = None
    n = spp // npass
    for i in range(n):
        img = np.array(mi.render(scene, seed=seed * 100003 + i, spp=npass), dtype=np.float64)[..., :3]
        acc = img if acc is None else acc + img
        print("seed %d: pass %d of %d, %.0f s" % (seed, i + 1, n, time.time() - t), flush=True)
    return acc / n

t = time.time()
a = half(seed_a)
b = half(seed_b)
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
