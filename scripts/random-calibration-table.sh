#!/usr/bin/env bash
# Regenerates the random lattice's calibration table, src/mechanics/random_calibration_table.inc:
# alpha = ks / kn -> the network's nu and E / En, measured by bench/bench_calibration on
# lattices of about 20 000 nodes (docs/model.md, "Random lattices"). About 20 minutes on 2
# cores. Usage: bash scripts/random-calibration-table.sh [BUILD_DIR]   (default: build)
set -euo pipefail
build=${1:-build}
here=$(cd "$(dirname "$0")/.." && pwd)
cmake --build "$build" --target bench_calibration -j2 >/dev/null
table=$(mktemp)
OPENBLAS_NUM_THREADS=1 "$build/bench/bench_calibration" table > "$table"
mv "$table" "$here/src/mechanics/random_calibration_table.inc"
echo "wrote $here/src/mechanics/random_calibration_table.inc; rebuild and run the tests" >&2
