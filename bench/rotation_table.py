#!/usr/bin/env python3
"""Rotation study on the peers' scene: mean and heap-to-heap scatter of the layer metrics per omega.

Usage: bench/rotation_table.py RUN_DIR   (the run directory of workflows/peer_liggghts.yaml after its
characterise stage). Prints a Markdown table: per omega, mean +- sample standard deviation over the
heaps of mean height, R_q, V_s, packing and bare fraction (1 - coverage), in mm, mm^2/s and -.
"""
import csv
import statistics
import sys

rows = list(csv.DictReader(open(sys.argv[1] + "/metrics.csv")))
by_omega = {}
for r in rows:
    by_omega.setdefault(float(r["omega"]), []).append(r)

def stat(values, scale):
    v = [x * scale for x in values]
    sd = statistics.stdev(v) if len(v) > 1 else float("nan")
    return statistics.mean(v), sd

print("| omega [rad/s] | heaps | mean height [mm] | R_q [mm] | V_s [mm^2/s] | packing | bare fraction |")
print("|---|---|---|---|---|---|---|")
for w in sorted(by_omega):
    rs = by_omega[w]
    cols = [("mean_height", 1e3), ("rq", 1e3), ("vs", 1e6), ("packing_fraction", 1.0)]
    cells = []
    for name, scale in cols:
        m, s = stat([float(r[name]) for r in rs], scale)
        cells.append(f"{m:.4f} ± {s:.4f}")
    m, s = stat([1 - float(r["coverage"]) for r in rs], 1.0)
    cells.append(f"{m:.3f} ± {s:.3f}")
    print(f"| {w:+.0f} | {len(rs)} | " + " | ".join(cells) + " |")
