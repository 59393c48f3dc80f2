#!/usr/bin/env bash
# Issue 19's GPU comparison on a machine with an NVIDIA GPU: lumis' GPU backend (`lumis bench
# --backend gpu`, several settings) against Mitsuba 3.9.1 `cuda_ad_rgb` (tools/mitsuba_cuda_time.py,
# its independent sampler and its low-discrepancy ones), MIS (power heuristic), on seed_cornell and
# veach_mis, back to back per scene, relMSE against the stored references at 256…MAX_SPP spp.
# Then a same-seed check of issue 20's techniques on the real GPU (GPU image against the CPU's).
# Usage: tools/gpu_vs_mitsuba.sh LUMIS_BINARY OUT_DIR [MAX_SPP]
# Needs: a Vulkan loader and NVIDIA's ICD for wgpu, python3 with mitsuba 3.9.1 and drjit 1.5.0,
# and ../shared/tools (scene_to_mitsuba.py, metrics.py) beside the checkout.
set -uo pipefail
cd "$(dirname "$0")/.."
lumis=$1
out=$2
max=${3:-4096}
mkdir -p "$out"
spps=$(python3 -c "print(','.join(str(256 << k) for k in range(20) if 256 << k <= $max))")
configs=(
    "independent:--sampler independent"
    "sobol:--sampler sobol"
    "best:--sampler sobol --light-selection bvh --light-sampling adaptive"
)
for scene in seed_cornell veach_mis; do
    json=tests/data/scenes/$scene.json
    ref=tests/data/refs/$scene.exr
    # Warm the GPU up (its clock idles low) and compile Mitsuba's kernel once.
    "$lumis" render "$json" --backend gpu --spp 256 -o "$out/warm.exr" > /dev/null
    for c in "${configs[@]}"; do
        name=${c%%:*}
        # shellcheck disable=SC2086
        "$lumis" bench "$json" --reference "$ref" --backend gpu --strategies mis --seed 1 \
            --spp-list "$spps" ${c#*:} -o "$out/${scene}_lumis_$name.csv" > /dev/null
        echo "lumis $scene $name"; cat "$out/${scene}_lumis_$name.csv"
    done
    for s in independent ldsampler multijitter orthogonal; do
        MI_SAMPLER=$s python3 tools/mitsuba_cuda_time.py "$json" "$ref" 256 "$max" \
            | tee "$out/${scene}_mitsuba_$s.jsonl"
    done
done
# Issue 20's techniques on the GPU: the same seed gives the CPU's image.
for c in "analytic_disk:--strategy mis --light-sampling solid-angle" \
    "analytic_polygon:--strategy mis --light-sampling projected-solid-angle" \
    "seed_cornell:--strategy mis-optimal" \
    "veach_mis:--strategy mis-optimal"; do
    scene=${c%%:*}
    for b in cpu gpu; do
        # shellcheck disable=SC2086
        "$lumis" render "tests/data/scenes/$scene.json" --backend $b --spp 64 --seed 5 ${c#*:} \
            -o "$out/same_$b.exr" > /dev/null
    done
    echo "same seed $scene (${c#*:}): $("$lumis" compare "$out/same_gpu.exr" "$out/same_cpu.exr")"
done
