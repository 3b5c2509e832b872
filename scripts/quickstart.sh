#!/bin/sh
# Builds the spreadmap program and its plugins (nothing else: no tests, no benchmarks, and no CUDA
# kernels on a machine without a GPU) and runs the quickstart workflow: 9 spreading simulations,
# their layer metrics, two surrogates and the process map, into runs/quickstart/ with report.html.
set -eu
cd "$(dirname "$0")/.."
jobs="${SPREADMAP_BUILD_JOBS:-2}"
start=$(date +%s)
phase() { echo "== $1 (expect $2; $(($(date +%s) - start)) s so far)"; }

phase "installing what is missing" "about 1.5 min on a fresh Debian 12, none when installed"
scripts/setup.sh
phase "configuring and building the program and its plugins" "about 4 min on 2 cores the first time, seconds after"
cmake --preset release >/dev/null
cmake --build build -j"$jobs" --target programs
phase "running workflows/quickstart.yaml" "about 40 s on 2 cores"
build/bin/spreadmap run workflows/quickstart.yaml --jobs "$jobs"
echo "== done in $(($(date +%s) - start)) s"
echo "the whole answer on one page: runs/quickstart/report.html (open it in a browser)"
echo "process map: runs/quickstart/map/map.png; best settings: runs/quickstart/map/optimum.json"
