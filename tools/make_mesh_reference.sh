#!/bin/sh
# Remakes the independent Mitsuba 3 reference of tests/data/scenes/textured_mesh.json (issue 17):
#   tests/data/refs/textured_mesh.exr      = (A + B) / 2
#   tests/data/refs/textured_mesh.var.exr  = (A - B)^2 / 4   (per pixel and channel)
# where A and B are two independent renders (seeds 1711 and 1712) of SPP samples per pixel each,
# made with Mitsuba 3.9.1's llvm_ad_rgb variant ('path' integrator) by this repository's copy of
# the shared converter, tools/scene_to_mitsuba.py, which adds textures (bitmap, checkerboard),
# quad uv and their checks to the shared one (its header lists what and how). The scene's mesh
# and texture files are made by tools/make_textured_mesh.py (deterministic).
# Tests never run this; it needs a Python with mitsuba==3.9.1 (and Debian's libllvm19):
#   MITSUBA_PY=/path/to/venv/bin/python tools/make_mesh_reference.sh
# Environment: MITSUBA_PY (default /tmp/mi/bin/python), SCENE_TO_MITSUBA (default
# tools/scene_to_mitsuba.py), SPP (default 32768), OUT (default tests/data/refs/textured_mesh).
# About 7 minutes of CPU per half on 2 cores (19 min wall each on the busy machine it ran on).
set -eu
cd "$(dirname "$0")/.."
PY=${MITSUBA_PY:-/tmp/mi/bin/python}
CONV=${SCENE_TO_MITSUBA:-tools/scene_to_mitsuba.py}
SPP=${SPP:-32768}
OUT=${OUT:-tests/data/refs/textured_mesh}
SCENE=tests/data/scenes/textured_mesh.json
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT

# The converter splits each half into independent single-pass renders of 128 spp (its LLVM
# memory bound at 160x120) with pass seeds SEED*100003 + i, so the two halves never share a seed.
nice "$PY" "$CONV" "$SCENE" "$SPP" llvm_ad_rgb "$TMP/a.exr" 1711
nice "$PY" "$CONV" "$SCENE" "$SPP" llvm_ad_rgb "$TMP/b.exr" 1712

"$PY" - "$CONV" "$TMP/a.exr" "$TMP/b.exr" "$OUT" <<'PYEOF'
import os, sys
import numpy as np
conv, pa, pb, out = sys.argv[1:]
sys.path.insert(0, os.path.dirname(os.path.abspath(conv)))
import mitsuba as mi
mi.set_variant("scalar_rgb")
from scene_to_mitsuba import write_exr

def read(p):
    return np.array(mi.Bitmap(p), dtype=np.float64)[..., :3]

a, b = read(pa), read(pb)
mean, var = (a + b) / 2, (a - b) ** 2 / 4
write_exr(out + ".exr", mean.astype(np.float32))
write_exr(out + ".var.exr", var.astype(np.float32))
# The reference's own noise, as in shared/refs/README.md: the expected relMSE of the mean
# against the converged image, mean over pixels and channels of var / (mean^2 + 1e-2).
print("relMSE of the reference's own noise: %.3g" % np.mean(var / (mean ** 2 + 1e-2)))
print("mean rgb", mean.reshape(-1, 3).mean(0), "non-finite", int((~np.isfinite(mean)).sum()))
# Largest relative standard deviation of a 32x32 block mean (per channel).
h, w = mean.shape[:2]
worst = 0.0
for y in range(0, h, 32):
    for x in range(0, w, 32):
        m = mean[y:y + 32, x:x + 32].reshape(-1, 3)
        v = var[y:y + 32, x:x + 32].reshape(-1, 3)
        worst = max(worst, float((np.sqrt(v.sum(0)) / len(m) / m.mean(0)).max()))
print("largest relative sd of a 32x32 block mean: %.2g" % worst)
PYEOF
