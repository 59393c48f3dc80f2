#!/usr/bin/env bash
# Issue 19's targets: lumis against Mitsuba 3 llvm_ad_rgb on the same cores, alternating runs.
# Per scene and seed, runs lumis' default MIS, lumis with the options in LUMIS_BEST, and Mitsuba
# with each sampler of MI_SAMPLERS; prints relMSE against the stored reference, seconds (lumis:
# the whole `lumis render` process; Mitsuba: mi.render only, as scene_to_mitsuba.py reports) and
# the equal-error efficiency 1/(relMSE·seconds) relative to Mitsuba's independent sampler.
# Usage: tools/mitsuba_vs_lumis.sh [SEEDS] [SPP] [OUT_DIR]
# Needs `pip install mitsuba==3.9.1 numpy`, Debian's libllvm19 and ../shared/tools.
set -euo pipefail
cd "$(dirname "$0")/.."
seeds=${1:-3}
spp=${2:-256}
out=${3:-out/mitsuba_vs_lumis}
best=${LUMIS_BEST:---light-selection bvh --light-sampling adaptive}
samplers=${MI_SAMPLERS:-independent ldsampler multijitter}
mkdir -p "$out"
cargo build --release -q -p lumis-app
lumis=${CARGO_TARGET_DIR:-target}/release/lumis
rows=$out/rows.txt
: > "$rows"
for scene in seed_cornell veach_mis; do
    ref=tests/data/refs/$scene.exr
    # Compile and cache Mitsuba's kernels once, outside the timing.
    python3 tools/mitsuba_sampler.py independent "tests/data/scenes/$scene.json" 4 llvm_ad_rgb "$out/warm.exr" 0 >/dev/null
    for ((seed = 0; seed < seeds; seed++)); do
        for cfg in "lumis_default:" "lumis_best:$best"; do
            name=${cfg%%:*}
            opts=${cfg#*:}
            img="$out/${scene}_${name}_$seed.exr"
            t0=$(date +%s.%N)
            # shellcheck disable=SC2086
            $lumis render "tests/data/scenes/$scene.json" --spp "$spp" --seed "$seed" --strategy mis $opts -o "$img" >/dev/null
            t1=$(date +%s.%N)
            r=$($lumis compare "$img" "$ref" | sed 's/relmse=\([^ ]*\).*/\1/')
            echo "$scene $name $seed $r $(python3 -c "print($t1 - $t0)")" >> "$rows"
        done
        for s in $samplers; do
            img="$out/${scene}_mi_${s}_$seed.exr"
            secs=$(python3 tools/mitsuba_sampler.py "$s" "tests/data/scenes/$scene.json" "$spp" llvm_ad_rgb "$img" "$seed" |
                python3 -c "import json,sys; print(json.load(sys.stdin)['seconds'])")
            r=$($lumis compare "$img" "$ref" | sed 's/relmse=\([^ ]*\).*/\1/')
            echo "$scene mitsuba_$s $seed $r $secs" >> "$rows"
        done
    done
done
python3 - "$rows" <<'PY'
import collections, statistics, sys
rows = collections.defaultdict(list)
for line in open(sys.argv[1]):
    scene, name, _seed, rel, secs = line.split()
    rows[(scene, name)].append((float(rel), float(secs)))
print(f"{'scene':14} {'renderer':24} {'relMSE':>10} {'seconds':>8} {'eff. vs mi independent':>22}")
for scene in dict.fromkeys(k[0] for k in rows):
    base = rows[(scene, "mitsuba_independent")]
    eff = lambda r: 1 / (statistics.mean(x for x, _ in r) * statistics.median(s for _, s in r))
    for (sc, name), r in rows.items():
        if sc == scene:
            print(f"{scene:14} {name:24} {statistics.mean(x for x, _ in r):10.3e} "
                  f"{statistics.median(s for _, s in r):8.2f} {eff(r) / eff(base):22.2f}")
PY
