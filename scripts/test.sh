#!/bin/sh
# The whole test suite from a fresh clone: installs what is missing, checks the source layout
# (scripts/check_layout.py), builds the release tree and runs every test, then builds the AddressSanitizer+UBSan tree and runs the unit, extremes and
# workflow tests under it. Tests labelled manual (run by hand) are left out, and so are those labelled
# gpu where no GPU is present (it says which).
set -eu
cd "$(dirname "$0")/.."
jobs="${SPREADMAP_BUILD_JOBS:-2}"

scripts/setup.sh --tests

echo "== layout: no include cycle between host/'s folders, no function over 80 lines in host/workflow/, no two files or types of one name, no error prefix outside host/core/error.cpp"
python3 scripts/check_layout.py

# The CUDA kernels compile here whenever nvcc is present, GPU or not (AUTO leaves them out without a GPU).
cuda=AUTO
if command -v nvcc >/dev/null 2>&1 || [ -x /usr/local/cuda/bin/nvcc ]; then cuda=ON; fi

echo "== release build (CUDA kernels: $cuda)"
cmake --preset release -DSPREADMAP_ENABLE_CUDA="$cuda"
cmake --build build -j"$jobs"
if command -v nvidia-smi >/dev/null 2>&1 && nvidia-smi -L 2>/dev/null | grep -q "^GPU"; then
  leave_out="manual"
  echo "== release tests (a GPU is present: the gpu tests run too; leaving out the label manual: it needs a person)"
else
  leave_out="gpu|manual"
  echo "== release tests (leaving out the labels gpu and manual: no GPU here, and manual needs a person)"
fi
ctest --test-dir build -j"$jobs" --output-on-failure -LE "$leave_out"

echo "== AddressSanitizer + UBSan build"
cmake --preset asan
cmake --build build-asan -j"$jobs"
echo "== sanitizer tests: unit, extremes, workflow (leaving out gpu and manual)"
ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
  ctest --test-dir build-asan -j"$jobs" --output-on-failure -L "unit|extremes|workflow" -LE "gpu|manual"
echo "== all tests passed"
