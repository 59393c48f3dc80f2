#!/bin/sh
# Export cross-check (issue 18, item 2): for each shared scene tests/data/scenes/NAME.json that
# `lumis export` accepts, Mitsuba 3.9.1 renders the exported XML itself (mi.load_file, variant
# llvm_ad_rgb) and the render is compared with the stored Mitsuba reference tests/data/refs/NAME.exr
# (+ .var.exr), which the independent converter made from the JSON, by a two-sample block z-test:
# per 32x32 block and channel z = (render block mean - reference block mean) / sd, sd^2 from the
# reference's variance image and the render's own, (A - B)^2 / 4 of two independent halves (seeds
# 2111 and 2112, SPP samples per pixel each, in passes of PASS). Critical |z|: Sidak family-wise
# alpha = 0.01 over each scene's blocks x 3 channels. Scenes the exporter refuses are reported and
# skipped. Prints one line per scene: NAME, blocks, worst |z|, critical |z|, ok/DIFFERENT, and the
# smallest relative block difference detected (critical |z| x sd / block mean; median, worst).
# Not a test (tests never run Mitsuba); it needs a Python with mitsuba==3.9.1 and a built lumis:
#   nice cargo build --release -p lumis-app && tools/check_export_with_mitsuba.sh [NAME ...]
# Environment: MITSUBA_PY (default /tmp/mi/bin/python), LUMIS (default target/release/lumis),
# SPP (default 256), PASS (default 64).
set -eu
cd "$(dirname "$0")/.."
PY=${MITSUBA_PY:-/tmp/mi/bin/python}
LUMIS=${LUMIS:-target/release/lumis}
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
if [ $# -eq 0 ]; then
    set -- $(ls tests/data/scenes/*.json | sed 's|.*/||; s|\.json$||')
fi
for NAME in "$@"; do
    if [ ! -f "tests/data/refs/$NAME.var.exr" ]; then
        echo "$NAME: no Mitsuba reference with a variance image, skipped"
        continue
    fi
    mkdir -p "$TMP/$NAME"
    if ! "$LUMIS" export "tests/data/scenes/$NAME.json" -o "$TMP/$NAME/$NAME.xml" \
        >"$TMP/$NAME/log" 2>&1; then
        echo "$NAME: the exporter refuses it, skipped: $(tail -1 "$TMP/$NAME/log")"
        continue
    fi
    nice "$PY" - "$TMP/$NAME/$NAME.xml" "tests/data/refs/$NAME" "$NAME" "${SPP:-256}" \
        "${PASS:-64}" <<'PYEOF'
import sys
from statistics import NormalDist
import numpy as np
import mitsuba as mi
mi.set_variant("llvm_ad_rgb")
xml, ref, name, spp, npass = sys.argv[1], sys.argv[2], sys.argv[3], int(sys.argv[4]), int(sys.argv[5])
scene = mi.load_file(xml)

def half(seed):
    n = spp // npass
    acc = sum(np.array(mi.render(scene, seed=seed * 100003 + i, spp=npass), dtype=np.float64)[..., :3]
              for i in range(n))
    return acc / n

a, b = half(2111), half(2112)
mean, var = (a + b) / 2, (a - b) ** 2 / 4
rm = np.array(mi.Bitmap(ref + ".exr"), dtype=np.float64)[..., :3]
rv = np.array(mi.Bitmap(ref + ".var.exr"), dtype=np.float64)[..., :3]
assert rm.shape == mean.shape, (rm.shape, mean.shape)
h, w = mean.shape[:2]
B = 32
zs, rel = [], []
for y in range(0, h, B):
    for x in range(0, w, B):
        s = (slice(y, y + B), slice(x, x + B))
        n = mean[s].shape[0] * mean[s].shape[1]
        d = mean[s].reshape(-1, 3).mean(0) - rm[s].reshape(-1, 3).mean(0)
        sd = np.sqrt((var[s].reshape(-1, 3).sum(0) + rv[s].reshape(-1, 3).sum(0)) / n ** 2)
        # A block black in both (sd 0) agrees; a difference with sd 0 does not.
        with np.errstate(divide="ignore", invalid="ignore"):
            zs.extend(np.where(sd > 0, np.abs(d) / sd, np.where(d == 0, 0.0, np.inf)))
        ref_mean = np.abs(rm[s].reshape(-1, 3).mean(0))
        rel.extend(sd[ref_mean > 0] / ref_mean[ref_mean > 0])
k = len(zs)
crit = NormalDist().inv_cdf(1 - (1 - 0.99 ** (1 / k)) / 2)
worst = max(zs)
# The smallest relative block difference the test detects: critical |z| x sd / block mean.
print("%s: %d blocks x 3 channels, worst |z| %.2f, critical %.2f, %s; detects a block difference"
      " of %.2g (median block) to %.2g (worst block) of the block mean"
      % (name, k // 3, worst, crit, "ok" if worst <= crit else "DIFFERENT",
         crit * np.median(rel), crit * max(rel)))
PYEOF
done
