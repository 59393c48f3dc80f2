#!/usr/bin/env bash
# Renders every shared scene with every strategy at 256 spp (seed 0) and prints the relMSE and
# RMSE against the independent reference, plus the render's own summary line.
# Usage: tools/relmse_table.sh [SPP] [OUT_DIR]
set -euo pipefail
cd "$(dirname "$0")/.."
spp=${1:-256}
out=${2:-out/relmse}
mkdir -p "$out"
cargo build --release -q -p lumis-app
lumis=target/release/lumis
printf '%-18s %-16s %-12s %-12s %s\n' scene strategy relmse rmse render
for scene in analytic_polygon analytic_disk seed_cornell veach_mis; do
    for s in light bsdf "mixture --mix-weight 0.5" "mis --heuristic power" "mis --heuristic balance"; do
        name=$(echo "$s" | tr -d ' -' | sed 's/mixweight/_w/; s/heuristic/_/')
        img="$out/${scene}_${name}.exr"
        # shellcheck disable=SC2086
        summary=$($lumis render "tests/data/scenes/$scene.json" --spp "$spp" --seed 0 --strategy $s -o "$img" | tail -n 1)
        read -r relmse rmse < <($lumis compare "$img" "tests/data/refs/$scene.exr" | sed 's/relmse=//; s/rmse=//')
        printf '%-18s %-16s %-12s %-12s %s\n' "$scene" "$name" "$relmse" "$rmse" "$summary"
    done
done
