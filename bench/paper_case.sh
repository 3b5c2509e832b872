#!/bin/bash
# One case of the study's scene measured end to end on this machine (heap, settling, spreading,
# characterisation: `spreadmap run` of a one-case workflow), beside LIGGGHTS's cost for the same
# scene, estimated from LIGGGHTS's serial per-particle-step throughput measured in the same run
# (bench/liggghts_rate.sh, the peers' scene) times the case's particle-steps at the same step.
#
# usage: bench/paper_case.sh [PRESET ...]   (default: paper, the 2 mm strip; paper_full: ~1 h on 2 cores)
# environment: BUILD (build folder, default ./build), WORK (default $BUILD/paper_case), THREADS (2),
#   SEED (1), U (the preset's 100 mm/s), SLEEP (false), LIGGGHTS_STEPS (20000), LIGGGHTS_REPEATS (3),
#   PEERS_DIR (the folder of the peers' LIGGGHTS decks). Every case runs from scratch.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${BUILD:-$root/build}
work=${WORK:-$build/paper_case}
threads=${THREADS:-2}
seed=${SEED:-1}
sleep_on=${SLEEP:-false}
presets=("$@")
[ ${#presets[@]} -gt 0 ] || presets=(paper)
spreadmap=$build/bin/spreadmap
[ -x "$spreadmap" ] || { echo "paper_case.sh: $spreadmap not built" >&2; exit 2; }
mkdir -p "$work"

echo "machine: $(lscpu | sed -n 's/^Model name: *//p' | head -1), $(nproc) hardware threads; load average at start $(cut -d' ' -f1-3 /proc/loadavg)"
for preset in "${presets[@]}"; do
  case $preset in  # the layer over the study's 50 mm of travel, across the strip or the study's square
    paper) region="{x: [35 mm, 85 mm], y: [0 mm, 2 mm]}" ;;
    paper_full) region="{x: [35 mm, 85 mm], y: [10 mm, 60 mm]}" ;;
    *) echo "paper_case.sh: unknown preset '$preset' (paper or paper_full)" >&2; exit 2 ;;
  esac
  speed=${U:+, U: $U}
  cat > "$work/$preset.yaml" <<YAML
version: 1
name: paper_case_$preset
scene: {preset: $preset, threads: $threads, time: {sleep: $sleep_on}}
stages:
  - simulate: {design: {type: list, cases: [{seed: $seed$speed}]}}
  - characterise: {region: $region, grid: 50 um}
YAML
  rm -rf "$work/$preset"
  start=$(date +%s.%N)
  "$spreadmap" run "$work/$preset.yaml" --jobs 1 --out "$work/$preset" > "$work/$preset.log" 2>&1
  end=$(date +%s.%N)
  python3 - "$work/$preset" "$preset" "$start" "$end" "$threads" <<'PY'
import csv, json, sys
run, preset, start, end, threads = sys.argv[1], sys.argv[2], float(sys.argv[3]), float(sys.argv[4]), sys.argv[5]
case = json.load(open(f"{run}/cases/c000/case.json"))
scene = json.load(open(f"{run}/cases/c000/scene.json"))
row = next(csv.DictReader(open(f"{run}/metrics.csv")))
n, dt = case["particles_start"], case["dt"]
settle_steps = round(scene["powder"]["settle_time"] / dt)
particle_steps = n * (settle_steps + case["steps"])
wall = end - start
print(f"{preset}: {n} spheres, {threads} threads, dt = {dt:.3g} s, {settle_steps} settling + {case['steps']} spreading steps"
      f" = {particle_steps:.3g} particle-steps")
print(f"  end to end {wall:.0f} s ({wall / 60:.1f} min); the spreading run {case['wall_seconds_last_run']:.0f} s at"
      f" {case['particle_steps_per_second']:.3g} particle-steps/s")
print(f"  layer: V_s {float(row['vs']) * 1e6:.2f} mm^2/s, R_q {float(row['rq']) * 1e6:.1f} um, packing"
      f" {float(row['packing_fraction']):.3f}, coverage {float(row['coverage']):.3f}, largest bare patch"
      f" {float(row['largest_bare_patch']) * 1e6:.3f} mm^2")
with open(f"{run}/particle_steps", "w") as f:
    f.write(f"{particle_steps}\n")
PY
done

if measured=$(STEPS=${LIGGGHTS_STEPS:-20000} REPEATS=${LIGGGHTS_REPEATS:-3} "$root/bench/liggghts_rate.sh" "$work/liggghts" | tail -1); then
  read -r rate version <<< "$measured"
  label="measured in this run on the peers' scene (liggghts $version, median of ${LIGGGHTS_REPEATS:-3})"
else
  rate=6.4e6 label="the peers' recorded figure (shared/peers), not measured in this run: LIGGGHTS is not installed"
fi
echo "LIGGGHTS serial: $rate particle-steps/s, $label"
for preset in "${presets[@]}"; do
  python3 -c "import sys; p = float(open(sys.argv[1]).read()); r = float(sys.argv[2]); \
print(f'  {sys.argv[3]}: LIGGGHTS serial would take {p / r / 60:.0f} min for its {p:.3g} particle-steps at the same step')" \
    "$work/$preset/particle_steps" "$rate" "$preset"
done
echo "load average at the end $(cut -d' ' -f1-3 /proc/loadavg)"
