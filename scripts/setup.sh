#!/bin/sh
# Installs the Debian 12 packages spreadmap builds against, only those missing.
# Runs apt-get as root, or through sudo. Usage: scripts/setup.sh [--tests]
set -eu

packages="cmake g++ make pkg-config libboost-dev libboost-program-options-dev libeigen3-dev libvtk9-dev
libyaml-cpp-dev nlohmann-json3-dev libspdlog-dev libgtest-dev libgmock-dev libbenchmark-dev xvfb xauth
libopenmpi-dev openmpi-bin"
if [ "${1:-}" = "--tests" ]; then
  # slurm-wlm and munge: the one-node Slurm of tests/cluster/slurm_localhost.sh (started by the test);
  # chromium and libxml2-utils (xmllint): the report's browser and well-formedness tests
  packages="$packages python3-numpy python3-sklearn slurm-wlm munge chromium libxml2-utils"
fi

missing=""
for p in $packages; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing="$missing $p"
  fi
done
[ -z "$missing" ] && exit 0

if [ "$(id -u)" -eq 0 ]; then
  sudo=""
elif command -v sudo >/dev/null 2>&1; then
  sudo="sudo"
else
  echo "setup: missing Debian packages:$missing" >&2
  echo "setup: run as root or install sudo, then run this again" >&2
  exit 1
fi
echo "setup: installing$missing"
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -q
# --no-install-recommends: keeps paraview (conflicts with libvtk9-dev) and other extras out.
$sudo apt-get install -y -q --no-install-recommends $missing
