#!/usr/bin/python3
"""docs/paper-scale.md, "The strip against the full width": one run's layer metrics beside the
heap-to-heap scatter of another's.

  bench/paper/compare.py RUN_DIR REFERENCE_RUN_DIR

Reads metrics.csv of both run directories. For each metric: the reference's mean and standard
deviation over its cases (heaps), the run's value (its mean when it has several cases) and the
difference in reference standard deviations. Standard library only.
"""
import csv
import statistics
import sys

# metric, display scale, unit
METRICS = [
    ("vs", 1e6, "mm^2/s"),
    ("rq", 1e6, "um"),
    ("packing_fraction", 1, "-"),
    ("coverage", 1, "-"),
    ("largest_bare_patch", 1e6, "mm^2"),
    ("solid_thickness", 1e6, "um"),
    ("mean_height", 1e6, "um"),
]


def rows(run_dir):
    with open(f"{run_dir}/metrics.csv", newline="") as f:
        return list(csv.DictReader(f))


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    run, ref = rows(sys.argv[1]), rows(sys.argv[2])
    if len(ref) < 2:
        sys.exit(f"{sys.argv[2]}/metrics.csv: the reference needs at least 2 cases (heaps) for a scatter")
    print(f"run: {sys.argv[1]} ({len(run)} case(s)); reference: {sys.argv[2]} ({len(ref)} heaps)")
    print(f"{'metric':<20} {'unit':<7} {'run':>10} {'reference mean':>15} {'sd':>9} {'(run - mean) / sd':>18}")
    for name, scale, unit in METRICS:
        ours = statistics.mean(float(r[name]) * scale for r in run)
        theirs = [float(r[name]) * scale for r in ref]
        mean, sd = statistics.mean(theirs), statistics.stdev(theirs)
        z = (ours - mean) / sd if sd > 0 else float("nan")
        print(f"{name:<20} {unit:<7} {ours:>10.4g} {mean:>15.4g} {sd:>9.3g} {z:>18.2f}")


if __name__ == "__main__":
    main()
