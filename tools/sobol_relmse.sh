#!/usr/bin/env bash
# relMSE at equal spp of the independent and the Sobol sampler (MIS, power heuristic), on
# seed_cornell and veach_mis at 16/64/256 spp, against the stored references, averaged over
# seeds 0..SEEDS-1 (docs/performance.md, "Sobol sampler (issue 19, item 1)").
# Usage: tools/sobol_relmse.sh [SEEDS] [OUT_DIR]
set -euo pipefail
cd "$(dirname "$0")/.."
exec tools/ab_relmse.sh "--strategy mis --heuristic power --sampler independent" \
    "--strategy mis --heuristic power --sampler sobol" "${1:-1}" "${2:-out/sobol_relmse}"
