#!/bin/bash
# Throughput on the peers' spreading scene, spreadmap beside LIGGGHTS, measured in the same run.
#
# When `liggghts` is on PATH (Debian: apt-get install --no-install-recommends liggghts), it measures
# LIGGGHTS's serial throughput on the peers' decks for the same number of spreading steps
# (bench/liggghts_rate.sh, the median of LIGGGHTS_REPEATS runs) and hands it to bench_peer_scene,
# which prints it beside spreadmap's 1- and 2-thread medians. Without LIGGGHTS the benchmark prints the peers' recorded figure (bench/README.md),
# labelled as not measured in this run.
#
# usage: bench/peer_scene.sh [extra bench_peer_scene arguments]
# environment: BUILD (build folder, default ./build), STEPS (20000), REPEATS (3), LIGGGHTS_REPEATS (3),
#   PEERS_DIR (the folder of the peers' LIGGGHTS decks), WORK (where the settled
#   heaps of both codes are kept and reused, default $BUILD/peer_scene).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${BUILD:-$root/build}
steps=${STEPS:-20000}
repeats=${REPEATS:-3}
lrepeats=${LIGGGHTS_REPEATS:-3}
peers=${PEERS_DIR:-/work/shared/peers/liggghts}
work=${WORK:-$build/peer_scene}
bench=$build/bin/bench_peer_scene
[ -x "$bench" ] || { echo "peer_scene.sh: $bench not built (cmake --build $build --target bench_peer_scene)" >&2; exit 2; }
mkdir -p "$work"

liggghts_args=()
if measured=$(STEPS=$steps REPEATS=$lrepeats PEERS_DIR=$peers "$root/bench/liggghts_rate.sh" "$work/liggghts" | tail -1); then
  read -r rate version <<< "$measured"
  liggghts_args=(--liggghts "$rate" --liggghts-label "measured in this run (liggghts $version, $steps steps, median of $lrepeats)")
else
  echo "LIGGGHTS not installed (or $peers missing): using the peers' recorded figure"
fi

heap=$work/heap_seed1.vtp
heap_args=(--save-heap "$heap")
[ -f "$heap" ] && heap_args=(--heap "$heap")
exec "$bench" --steps "$steps" --repeats "$repeats" "${heap_args[@]}" "${liggghts_args[@]}" "$@"
