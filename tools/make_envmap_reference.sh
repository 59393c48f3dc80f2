#!/bin/sh
# Remakes the independent Mitsuba 3 reference of tests/data/scenes/envmap_objects.json (issue 16):
#   tests/data/refs/envmap_objects.exr      = (A + B) / 2
#   tests/data/refs/envmap_objects.var.exr  = (A - B)^2 / 4   (per pixel and channel)
# where A and B are two independent renders (seeds 1611 and 1612) of SPP samples per pixel each,
# made by the shared converter with Mitsuba 3.9.1's llvm_ad_rgb variant ('path' integrator; the
# scene's background.envmap becomes Mitsuba's 'envmap' emitter with the scene's scale and a
# to_world rotation of rotate_y_deg about +y). The map, tests/data/scenes/envmap_test_sky.exr, is
# made by renderer/examples/make_sky.rs (the command is in tests/data/refs/README.md).
# Tests never run this; it needs a Python with mitsuba==3.9.1 (and Debian's libllvm19):
#   MITSUBA_PY=/path/to/venv/bin/python tools/make_envmap_reference.sh
# Environment: MITSUBA_PY (default /tmp/mi/bin/python), SCENE_TO_MITSUBA (default
# ../shared/tools/scene_to_mitsuba.py, relative to the repository root), SPP (default 32768),
# OUT (default tests/data/refs/envmap_objects). About 4 minutes per half on 2 cores.
set -eu
cd "$(dirname "$0")/.."
PY=${MITSUBA_PY:-/tmp/mi/bin/python}
CONV=${SCENE_TO_MITSUBA:-../shared/tools/scene_to_mitsuba.py}
SPP=${SPP:-32768}
OUT=${OUT:-tests/data/refs/envmap_objects}
SCENE=tests/data/scenes/envmap_objects.json
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT

# The converter splits each half into independent single-pass renders of 64 spp (its LLVM
# memory bound at 192x192) with pass seeds SEED*100003 + i, so the two halves never share a seed.
nice "$PY" "$CONV" "$SCENE" "$SPP" llvm_ad_rgb "$TMP/a.exr" 1611
nice "$PY" "$CONV" "$SCENE" "$SPP" llvm_ad_rgb "$TMP/b.exr" 1612

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
