#!/bin/bash
# The GPU batch measurement of issue 41, for a machine with a CUDA device, within 10 minutes: the
# paper map's strip cases stepping at once (1, 8 and 45 of them, bench_gpu_batch) and the full-width
# scene alone (bench/paper/full_periodic.yaml, 235,000 spheres), each from a heap settled on the GPU.
# Prints the device, the host and every figure; the gpu tests (ctest -L gpu) are the bitwise checks.
#
# usage: bench/gpu_batch.sh   environment: BUILD (default ./build), STEPS (strip steps a case, 10000),
#   FULL_STEPS (full-width steps, 2000)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${BUILD:-$root/build}
batch=$build/bin/bench_gpu_batch
[ -x "$batch" ] || { echo "gpu_batch.sh: $batch not built (a CUDA build: -DSPREADMAP_ENABLE_CUDA=ON)" >&2; exit 2; }
nvidia-smi --query-gpu=name,memory.total,driver_version --format=csv,noheader || true
timeout 240 "$batch" --cases 1,8,45 --steps "${STEPS:-10000}"
timeout 300 "$batch" --workflow "$root/bench/paper/full_periodic.yaml" --cases 1 --steps "${FULL_STEPS:-2000}"
