#!/bin/bash
# LIGGGHTS's serial throughput on the peers' spreading scene, measured here and now.
#
# Runs the peers' LIGGGHTS decks (spread/in.settle once, then spread/in.spread at omega = 0 for STEPS
# spreading steps, REPEATS times, one process) and prints the median of particle-steps/s from each
# run's "Loop time" (mean atom count x steps / loop time, as the peers' comparison of LIGGGHTS and
# LAMMPS counts it). The last line of stdout is "RATE VERSION"; progress goes to stderr. Exits 3 when
# LIGGGHTS is not installed (Debian: apt-get install --no-install-recommends liggghts) or the decks
# are missing.
#
# usage: bench/liggghts_rate.sh WORK_DIR
# environment: STEPS (20000), REPEATS (3), PEERS_DIR (the folder of the peers' LIGGGHTS decks)
set -euo pipefail
work=${1:?usage: liggghts_rate.sh WORK_DIR}
steps=${STEPS:-20000}
repeats=${REPEATS:-3}
peers=${PEERS_DIR:-/work/shared/peers/liggghts}
dt=7.5e-7
command -v liggghts >/dev/null && [ -f "$peers/spread/in.spread" ] || exit 3

mkdir -p "$work"
cp "$peers/spread/in.settle" "$peers/spread/in.spread" "$peers/spread/common.liggghts" "$work/"
python3 "$peers/make_roller_stl.py" "$work/roller.stl" 5e-3 0 2.5e-3 180 6e-3 5.5e-3
cd "$work"
if [ ! -f settled.restart ]; then
  echo "LIGGGHTS: settling its heap (in.settle, about 2 minutes) ..." >&2
  # stdout redirected, not -screen none: LIGGGHTS 3.8 crashes reading the STL without a screen
  liggghts -in in.settle -log log.settle > screen.settle 2>&1
fi
# tspread just under steps x dt, so that in.spread's ceil(tspread/dt) is exactly `steps`
tspread=$(python3 -c "print(($steps - 0.5) * $dt)")
rates=()
for r in $(seq 1 "$repeats"); do
  liggghts -in in.spread -var omega 0 -var tag bench$r -var tspread "$tspread" -var trelax 0 \
    -log log.bench$r > screen.bench$r 2>&1
  rate=$(python3 - "log.bench$r" <<'PY'
import re, sys
text = open(sys.argv[1]).read()
loop = re.search(r'Loop time of ([0-9.eE+-]+) on (\d+) procs for (\d+) steps with (\d+) atoms', text)
rows = [l.split() for l in text[:loop.start()].splitlines() if re.match(r'^\s*\d+\s+\d+\s+[-0-9.eE+]+', l)]
atoms = [int(r[1]) for r in rows] or [int(loop.group(4))]
print(sum(atoms) / len(atoms) * int(loop.group(3)) / float(loop.group(1)))
PY
)
  echo "LIGGGHTS repeat $r, 1 process: $rate particle-steps/s" >&2
  rates+=("$rate")
done
median=$(printf '%s\n' "${rates[@]}" | sort -g | python3 -c "import sys; v=[float(x) for x in sys.stdin]; n=len(v); print(v[n//2] if n%2 else (v[n//2-1]+v[n//2])/2)")
echo "$median $(dpkg-query -W -f '${Version}' liggghts 2>/dev/null || echo '?')"
