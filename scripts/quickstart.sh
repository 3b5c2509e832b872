#!/bin/sh
# Builds spreadmap and runs the quickstart workflow: 9 spreading simulations, their layer metrics,
# two surrogates and the process map, into runs/quickstart/ (a few minutes on 2 cores).
set -eu
cd "$(dirname "$0")/.."
jobs="${SPREADMAP_BUILD_JOBS:-2}"
scripts/setup.sh
cmake --preset release
cmake --build build -j"$jobs"
build/bin/spreadmap run workflows/quickstart.yaml --jobs "$jobs"
echo "process map: runs/quickstart/map/map.png; best settings: runs/quickstart/map/optimum.json"
