#!/bin/sh
# Remakes the independent Mitsuba 3 reference of tests/data/scenes/glass_room.json:
#   tests/data/refs/glass_room.exr      = (A + B) / 2
#   tests/data/refs/glass_room.var.exr  = (A - B)^2 / 4   (per pixel and channel)
# where A and B are two independent renders (seeds 1511 and 1512) of SPP samples per pixel each,
# made by the shared converter with Mitsuba 3.9.1's llvm_ad_rgb variant ('path' integrator).
# Tests never run this; it needs a Python with mitsuba==3.9.1 (and Debian's libllvm19):
#   MITSUBA_PY=/path/to/venv/bin/python tools/make_glass_reference.sh
# Environment: MITSUBA_PY (default /tmp/mi/bin/python), SCENE_TO_MITSUBA (default
# ../shared/tools/scene_to_mitsuba.py, relative to the repository root), SPP (default 8192),
# OUT (default tests/data/refs/glass_room). About 5 minutes per half on 2 cores.
set -eu
cd "$(dirname "$0")/.."
PY=${MITSUBA_PY:-/tmp/mi/bin/python}
CONV=${SCENE_TO_MITSUBA:-../shared/tools/scene_to_mitsuba.py}
SPP=${SPP:-8192}
OUT=${OUT:-tests/data/refs/glass_room}
SCENE=tests/data/scenes/glass_room.json
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT

# The converter splits each half into independent single-pass renders of 64 spp (its LLVM
# memory bound at 192x192) with pass seeds SEED*100003 + i, so the two halves never share a seed.
nice "$PY" "$CONV" "$SCENE" "$SPP" llvm_ad_rgb "$TMP/a.exr" 1511
nice "$PY" "$CONV" "$SCENE" "$SPP" llvm_ad_rgb "$TMP/b.exr" 1512

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
PYEOF
