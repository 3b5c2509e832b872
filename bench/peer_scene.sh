#!/bin/bash
# Throughput on the peers' spreading scene, spreadmap beside LIGGGHTS, measured in the same run.
#
# When `liggghts` is on PATH (Debian: apt-get install --no-install-recommends liggghts), it runs the
# peers' LIGGGHTS decks (spread/in.settle, then spread/in.spread at omega = 0, under PEERS_DIR) for the
# same number of spreading steps, LIGGGHTS_REPEATS times, takes the median of particle-steps/s from
# each run's "Loop time" (mean atom count x steps / loop time, as the peers' comparison of LIGGGHTS
# and LAMMPS counts it), and hands it to bench_peer_scene, which prints it beside spreadmap's 1- and
# 2-thread medians. Without LIGGGHTS the benchmark prints the peers' recorded figure (bench/README.md),
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
dt=7.5e-7
bench=$build/bin/bench_peer_scene
[ -x "$bench" ] || { echo "peer_scene.sh: $bench not built (cmake --build $build --target bench_peer_scene)" >&2; exit 2; }
mkdir -p "$work"

liggghts_args=()
if command -v liggghts >/dev/null && [ -f "$peers/spread/in.spread" ]; then
  lw=$work/liggghts
  mkdir -p "$lw"
  cp "$peers/spread/in.settle" "$peers/spread/in.spread" "$peers/spread/common.liggghts" "$lw/"
  python3 "$peers/make_roller_stl.py" "$lw/roller.stl" 5e-3 0 2.5e-3 180 6e-3 5.5e-3
  cd "$lw"
  if [ ! -f settled.restart ]; then
    echo "LIGGGHTS: settling its heap (in.settle, about 2 minutes) ..."
    # stdout redirected, not -screen none: LIGGGHTS 3.8 crashes reading the STL without a screen
    liggghts -in in.settle -log log.settle > screen.settle 2>&1
  fi
  # tspread just under steps x dt, so that in.spread's ceil(tspread/dt) is exactly `steps`
  tspread=$(python3 -c "print(($steps - 0.5) * $dt)")
  rates=()
  for r in $(seq 1 "$lrepeats"); do
    liggghts -in in.spread -var omega 0 -var tag bench$r -var tspread "$tspread" -var trelax 0 \
      -log log.bench$r > screen.bench$r 2>&1
    rate=$(python3 - "log.bench$r" <<'EOF'
import re, sys
text = open(sys.argv[1]).read()
loop = re.search(r'Loop time of ([0-9.eE+-]+) on (\d+) procs for (\d+) steps with (\d+) atoms', text)
rows = [l.split() for l in text[:loop.start()].splitlines() if re.match(r'^\s*\d+\s+\d+\s+[-0-9.eE+]+', l)]
atoms = [int(r[1]) for r in rows] or [int(loop.group(4))]
print(sum(atoms) / len(atoms) * int(loop.group(3)) / float(loop.group(1)))
EOF
)
    echo "LIGGGHTS repeat $r, 1 process: $rate particle-steps/s"
    rates+=("$rate")
  done
  cd "$root"
  median=$(printf '%s\n' "${rates[@]}" | sort -g | python3 -c "import sys; v=[float(x) for x in sys.stdin]; n=len(v); print(v[n//2] if n%2 else (v[n//2-1]+v[n//2])/2)")
  version=$(dpkg-query -W -f '${Version}' liggghts 2>/dev/null || echo "?")
  liggghts_args=(--liggghts "$median" --liggghts-label "measured in this run (liggghts $version, $steps steps, median of $lrepeats)")
else
  echo "LIGGGHTS not installed (or $peers missing): using the peers' recorded figure"
fi

heap=$work/heap_seed1.vtp
heap_args=(--save-heap "$heap")
[ -f "$heap" ] && heap_args=(--heap "$heap")
exec "$bench" --steps "$steps" --repeats "$repeats" "${heap_args[@]}" "${liggghts_args[@]}" "$@"
