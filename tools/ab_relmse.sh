#!/usr/bin/env bash
# Two settings of `lumis render` side by side (a technique off and on): relMSE against the stored
# references at equal spp, averaged over seeds 0..SEEDS-1, the mean render seconds, and the
# equal-time efficiency ratio (relMSE·seconds of A over that of B; > 1: B is more efficient).
# Runs alternate A and B per seed, so machine load affects both alike.
# Usage: tools/ab_relmse.sh "OPTIONS A" "OPTIONS B" [SEEDS] [OUT_DIR] [SCENES] [SPP_LIST]
#   e.g. tools/ab_relmse.sh "--strategy mis --sampler independent" "--strategy mis --sampler sobol"
# SCENES defaults to "seed_cornell veach_mis", SPP_LIST to "16 64 256". A scene is read from
# tests/data/scenes/, else from assets/ (plastic_lights, whose stored reference is a lumis render).
# REF_DIR (default tests/data/refs) holds the references SCENE.exr: another folder for renders
# that are not the full image (e.g. references rendered with --max-depth 2).
# LUMIS_A / LUMIS_B: other binaries for A / B (e.g. another worktree's build, to compare with the
# code before a change), the one built here by default.
set -euo pipefail
cd "$(dirname "$0")/.."
a=$1
b=$2
seeds=${3:-1}
out=${4:-out/ab_relmse}
scenes=${5:-seed_cornell veach_mis}
spps=${6:-16 64 256}
refs=${REF_DIR:-tests/data/refs}
mkdir -p "$out"
cargo build --release -q -p lumis-app
lumis=${CARGO_TARGET_DIR:-target}/release/lumis
lumis_a=${LUMIS_A:-$lumis}
lumis_b=${LUMIS_B:-$lumis}
echo "A: $lumis_a $a"
echo "B: $lumis_b $b"
printf '%-16s %5s %-11s %-11s %-9s %-13s %s\n' scene spp relmse_A relmse_B A/B seconds_A/B efficiency_B/A
for scene in $scenes; do
    for spp in $spps; do
        declare -A rel=([a]=0 [b]=0) secs=([a]=0 [b]=0)
        for ((seed = 0; seed < seeds; seed++)); do
            for side in a b; do
                opts=$a
                bin=$lumis_a
                [ "$side" = b ] && opts=$b && bin=$lumis_b
                img="$out/${scene}_${spp}_${side}_${seed}.exr"
                file="tests/data/scenes/$scene.json"
                [ -f "$file" ] || file="assets/$scene.json"
                # shellcheck disable=SC2086
                summary=$($bin render "$file" --spp "$spp" --seed "$seed" \
                    $opts -o "$img" | tail -n 1)
                s=$(echo "$summary" | sed 's/.*seconds=\([^ ]*\).*/\1/')
                r=$($lumis compare "$img" "$refs/$scene.exr" | sed 's/relmse=\([^ ]*\).*/\1/')
                rel[$side]=$(python3 -c "print(${rel[$side]} + $r / $seeds)")
                secs[$side]=$(python3 -c "print(${secs[$side]} + $s / $seeds)")
            done
        done
        python3 - "$scene" "$spp" "${rel[a]}" "${rel[b]}" "${secs[a]}" "${secs[b]}" <<'PY'
import sys
scene, spp, ra, rb, sa, sb = sys.argv[1], sys.argv[2], *map(float, sys.argv[3:])
print(f"{scene:16} {spp:>5} {ra:<11.4e} {rb:<11.4e} {ra / rb:<9.2f} {sa:.2f}/{sb:.2f}{'':4} {ra * sa / (rb * sb):.2f}")
PY
    done
done
