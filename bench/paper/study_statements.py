#!/usr/bin/python3
"""docs/study.md, "The study's statements": each trend the reference study states, held against a
run's metrics.csv (standard library only).

  bench/paper/study_statements.py RUN_DIR

1. R_q against the rotation: at each U, the least-squares slope of R_q over omega and the sign of
   R_q(omega = -20) - R_q(omega = +20). The study: R_q rises from anticlockwise (+) to clockwise (-);
   under paper-notes.md's convention (omega > 0 turns the roller like a wheel rolling forward) that
   reads "R_q falls as omega grows"; the other reading of the study's words is the opposite sign.
2. V_s against U: at each omega, whether V_s rises with every step of U.
3. The layer thickness (mean height) against the rotation, for the same two readings.
"""
import csv
import statistics
import sys
from collections import defaultdict


def slope(xs, ys):
    mx, my = statistics.fmean(xs), statistics.fmean(ys)
    sxx = sum((x - mx) ** 2 for x in xs)
    return sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sxx


def main(run_dir):
    with open(f"{run_dir}/metrics.csv", newline="") as f:
        rows = [r for r in csv.DictReader(f)]
    by_u, by_w = defaultdict(list), defaultdict(list)
    for r in rows:
        u, w = float(r["U"]), float(r["omega"])
        rec = (u, w, float(r["vs"]), float(r["rq"]), float(r["mean_height"]))
        by_u[u].append(rec)
        by_w[w].append(rec)

    print("1. R_q against omega at each U (slope in um per rad/s; R_q(-20) - R_q(+20) in um)")
    falls = 0
    for u in sorted(by_u):
        pts = sorted(by_u[u], key=lambda p: p[1])
        s = slope([p[1] for p in pts], [p[3] * 1e6 for p in pts])
        ends = (pts[0][3] - pts[-1][3]) * 1e6
        falls += s < 0
        print(f"   U = {u * 1e3:5.1f} mm/s: slope {s:+.3f}, R_q(-20) - R_q(+20) = {ends:+.2f}")
    print(f"   R_q falls as omega grows (+ to - raises R_q, this project's convention) at {falls} of {len(by_u)} speeds")

    print("2. V_s against U at each omega (rises at every step?)")
    rising = 0
    for w in sorted(by_w):
        pts = sorted(by_w[w], key=lambda p: p[0])
        ok = all(b[2] > a[2] for a, b in zip(pts, pts[1:]))
        rising += ok
        print(f"   omega = {w:+5.1f} rad/s: V_s " + " ".join(f"{p[2] * 1e6:.2f}" for p in pts) +
              f" mm^2/s: {'rises' if ok else 'does NOT rise at every step'}")
    print(f"   V_s rises with U at every step at {rising} of {len(by_w)} rotations")

    print("3. layer mean height against omega at each U (slope in um per rad/s)")
    for u in sorted(by_u):
        pts = sorted(by_u[u], key=lambda p: p[1])
        s = slope([p[1] for p in pts], [p[4] * 1e6 for p in pts])
        print(f"   U = {u * 1e3:5.1f} mm/s: slope {s:+.3f}")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "runs/paper")
