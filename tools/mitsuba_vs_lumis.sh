#!/usr/bin/env bash
# Issue 19's targets: lumis against Mitsuba 3 llvm_ad_rgb on the same cores, alternating runs.
# Per scene and seed, runs each lumis configuration of LUMIS_CONFIGS (MIS) and Mitsuba with each
# sampler of MI_SAMPLERS; prints relMSE against the stored reference, seconds and the equal-error
# efficiency 1/(relMSE·seconds) relative to Mitsuba's independent sampler.
# Seconds: lumis the whole `lumis render` process (load, build, render, write); Mitsuba mi.render
# only, as scene_to_mitsuba.py reports. CLOCK=wall (default) times wall seconds, for an idle
# machine; CLOCK=cpu the CPU seconds of all threads (lumis: perf stat task-clock of the process;
# Mitsuba: process time during mi.render), which other work on a shared machine inflates far less.
# Usage: tools/mitsuba_vs_lumis.sh [SEEDS] [SPP] [OUT_DIR]
#   LUMIS_CONFIGS="name:options;name:options" (default: default settings, and the best found)
#   LUMIS=path/to/lumis (default: build and use target/release/lumis)
# Needs `pip install mitsuba==3.9.1 numpy`, Debian's libllvm19 and ../shared/tools; CLOCK=cpu
# needs perf (Debian's linux-perf).
set -euo pipefail
cd "$(dirname "$0")/.."
seeds=${1:-3}
spp=${2:-256}
out=${3:-out/mitsuba_vs_lumis}
clock=${CLOCK:-wall}
configs=${LUMIS_CONFIGS:-"default:;best:--sampler sobol --light-selection bvh --light-sampling adaptive"}
samplers=${MI_SAMPLERS:-independent ldsampler multijitter}
scenes=${SCENES:-seed_cornell veach_mis}
mkdir -p "$out"
if [ -z "${LUMIS:-}" ]; then
    cargo build --release -q -p lumis-app
    LUMIS=${CARGO_TARGET_DIR:-target}/release/lumis
fi
export MI_CLOCK=$clock
rows=$out/rows.txt
: > "$rows"
IFS=';' read -r -a config_list <<< "$configs"
for scene in $scenes; do
    ref=tests/data/refs/$scene.exr
    # Compile and cache Mitsuba's kernels once, outside the timing.
    python3 tools/mitsuba_sampler.py independent "tests/data/scenes/$scene.json" 4 llvm_ad_rgb "$out/warm.exr" 0 >/dev/null
    for ((seed = 0; seed < seeds; seed++)); do
        for cfg in "${config_list[@]}"; do
            name=lumis_${cfg%%:*}
            opts=${cfg#*:}
            img="$out/${scene}_${name}_$seed.exr"
            # shellcheck disable=SC2086
            if [ "$clock" = cpu ]; then
                secs=$(perf stat -x, -e task-clock "$LUMIS" render "tests/data/scenes/$scene.json" \
                    --spp "$spp" --seed "$seed" --strategy mis $opts -o "$img" 2>&1 >/dev/null |
                    grep task-clock | cut -d, -f1 | python3 -c "import sys; print(float(sys.stdin.read()) / 1000)")
            else
                t0=$(date +%s.%N)
                "$LUMIS" render "tests/data/scenes/$scene.json" --spp "$spp" --seed "$seed" \
                    --strategy mis $opts -o "$img" >/dev/null
                t1=$(date +%s.%N)
                secs=$(python3 -c "print($t1 - $t0)")
            fi
            r=$("$LUMIS" compare "$img" "$ref" | sed 's/relmse=\([^ ]*\).*/\1/')
            echo "$scene $name $seed $r $secs" >> "$rows"
        done
        for s in $samplers; do
            img="$out/${scene}_mi_${s}_$seed.exr"
            secs=$(python3 tools/mitsuba_sampler.py "$s" "tests/data/scenes/$scene.json" "$spp" llvm_ad_rgb "$img" "$seed" |
                python3 -c "import json,sys; print(json.load(sys.stdin)['seconds'])")
            r=$("$LUMIS" compare "$img" "$ref" | sed 's/relmse=\([^ ]*\).*/\1/')
            echo "$scene mitsuba_$s $seed $r $secs" >> "$rows"
        done
    done
done
echo "clock: $clock; spp $spp; seeds 0..$((seeds - 1)); seconds the median"
echo "efficiency 1/(relMSE·seconds) relative to Mitsuba independent's, by the mean and by the median"
echo "relMSE (a single firefly moves the mean of a heavy-tailed error; the median is robust)"
python3 - "$rows" <<'PY'
import collections, statistics, sys
rows = collections.defaultdict(list)
for line in open(sys.argv[1]):
    scene, name, _seed, rel, secs = line.split()
    rows[(scene, name)].append((float(rel), float(secs)))
print(f"{'scene':14} {'renderer':24} {'relMSE mean':>11} {'median':>10} {'seconds':>8} "
      f"{'eff. (mean)':>11} {'eff. (median)':>13}")
for scene in dict.fromkeys(k[0] for k in rows):
    base = rows[(scene, "mitsuba_independent")]
    secs = lambda r: statistics.median(s for _, s in r)
    eff = lambda r, avg: 1 / (avg([x for x, _ in r]) * secs(r))
    for (sc, name), r in rows.items():
        if sc == scene:
            m, md = statistics.mean, statistics.median
            print(f"{scene:14} {name:24} {m(x for x, _ in r):11.3e} {md(x for x, _ in r):10.3e} "
                  f"{secs(r):8.2f} {eff(r, m) / eff(base, m):11.2f} {eff(r, md) / eff(base, md):13.2f}")
PY
