#!/usr/bin/env bash
# relMSE at equal spp of the independent and the Sobol sampler (MIS, power heuristic), on
# seed_cornell and veach_mis at 16/64/256 spp, against the stored references, averaged over
# seeds 0..SEEDS-1 (docs/performance.md, "Sobol sampler (issue 19, item 1)").
# Usage: tools/sobol_relmse.sh [SEEDS] [OUT_DIR]
set -euo pipefail
cd "$(dirname "$0")/.."
seeds=${1:-1}
out=${2:-out/sobol_relmse}
mkdir -p "$out"
cargo build --release -q -p lumis-app
lumis=target/release/lumis
printf '%-14s %5s %-12s %-12s %-12s %s\n' scene spp independent sobol ratio seconds_ind/sobol
for scene in seed_cornell veach_mis; do
    for spp in 16 64 256; do
        row=()
        secs=()
        for sampler in independent sobol; do
            total=0
            t=0
            for ((seed = 0; seed < seeds; seed++)); do
                img="$out/${scene}_${spp}_${sampler}_${seed}.exr"
                summary=$($lumis render "tests/data/scenes/$scene.json" --spp "$spp" --seed "$seed" \
                    --strategy mis --heuristic power --sampler "$sampler" -o "$img" | tail -n 1)
                s=$(echo "$summary" | sed 's/.*seconds=\([^ ]*\).*/\1/')
                r=$($lumis compare "$img" "tests/data/refs/$scene.exr" | sed 's/relmse=\([^ ]*\).*/\1/')
                total=$(python3 -c "print($total + $r)")
                t=$(python3 -c "print($t + $s)")
            done
            row+=("$(python3 -c "print(f'{$total / $seeds:.4e}')")")
            secs+=("$(python3 -c "print(f'{$t / $seeds:.2f}')")")
        done
        ratio=$(python3 -c "print(f'{${row[0]} / ${row[1]}:.2f}')")
        printf '%-14s %5s %-12s %-12s %-12s %s\n' "$scene" "$spp" "${row[0]}" "${row[1]}" "$ratio" "${secs[0]}/${secs[1]}"
    done
done
