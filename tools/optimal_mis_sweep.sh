#!/usr/bin/env bash
# MIS with optimal weights against MIS with the balance and the power heuristic
# (docs/techniques.md, "Optimal MIS weights"): every scene rendered once per strategy, seed and
# spp, the three strategies alternating per seed so machine load affects them alike. Prints one
# row per scene and spp (every scene at the first spp, then at the next): the mean relMSE (over
# seeds 0..SEEDS-1) against the stored reference of each strategy, the relMSE ratios
# balance/optimal and power/optimal at equal spp (> 1: optimal is better), the mean CPU seconds
# (user + system of the whole `lumis render` process, scene loading and the EXR included) and the
# equal-time efficiency ratios, relMSE·CPU-seconds of balance (power) over that of optimal.
# OUT_DIR/runs.txt keeps every run: scene spp strategy seed relmse user system. EXTRA (default
# none) adds options to every render, e.g. "--max-depth 2"; REF_DIR (default tests/data/refs)
# holds the references SCENE.exr.
# Usage: tools/optimal_mis_sweep.sh [SEEDS] [OUT_DIR] [SCENES] [SPP_LIST]
set -euo pipefail
cd "$(dirname "$0")/.."
seeds=${1:-3}
out=${2:-out/optimal_mis}
scenes=${3:-analytic_polygon analytic_disk seed_cornell veach_mis glass_room envmap_objects textured_mesh}
spps=${4:-16 64 256}
extra=${EXTRA:-}
refs=${REF_DIR:-tests/data/refs}
mkdir -p "$out"
cargo build --release -q -p lumis-app
lumis=${CARGO_TARGET_DIR:-target}/release/lumis
log="$out/runs.txt"
: >"$log"
for spp in $spps; do
    for scene in $scenes; do
        for ((seed = 0; seed < seeds; seed++)); do
            for s in balance power optimal; do
                opts="--strategy mis --heuristic $s"
                [ "$s" = optimal ] && opts="--strategy mis-optimal"
                img="$out/${scene}_${spp}_${s}_${seed}.exr"
                # shellcheck disable=SC2086
                cpu=$( { /usr/bin/time -f 'cpu %U %S' $lumis render "tests/data/scenes/$scene.json" \
                    --spp "$spp" --seed "$seed" $opts $extra -o "$img" >/dev/null; } 2>&1 | tail -n 1)
                r=$($lumis compare "$img" "$refs/$scene.exr" | sed 's/relmse=\([^ ]*\).*/\1/')
                echo "$scene $spp $s $seed $r ${cpu#cpu }" >>"$log"
            done
        done
        python3 - "$log" "$scene" "$spp" <<'PY'
import sys
from collections import defaultdict
log, scene, spp = sys.argv[1:]
rel, cpu, n = defaultdict(float), defaultdict(float), defaultdict(int)
for line in open(log):
    sc, sp, s, _seed, r, u, k = line.split()
    if sc == scene and sp == spp:
        rel[s] += float(r); cpu[s] += float(u) + float(k); n[s] += 1
for s in rel:
    rel[s] /= n[s]; cpu[s] /= n[s]
b, p, o = "balance", "power", "optimal"
print(f"{scene:16} {spp:>4} relmse b={rel[b]:.4e} p={rel[p]:.4e} o={rel[o]:.4e}"
      f"  b/o={rel[b] / rel[o]:.3f} p/o={rel[p] / rel[o]:.3f}"
      f"  cpu b={cpu[b]:.2f} p={cpu[p]:.2f} o={cpu[o]:.2f}"
      f"  eff b/o={rel[b] * cpu[b] / (rel[o] * cpu[o]):.3f} p/o={rel[p] * cpu[p] / (rel[o] * cpu[o]):.3f}",
      flush=True)
PY
    done
done
