#!/usr/bin/env python3
"""Sampling noise of the layer's segregation metrics, by bootstrap over the layer's particles.

Usage: bench/segregation_noise.py CASE_DIR X0_MM X1_MM   (a case folder with state.vtp written in
ASCII, as spreadmap writes it; X0..X1 the sampling region along x in mm, the whole width in y).

The layer here is every sphere with its centre in X0 <= x < X1 and below 0.2 mm: close to what
metrics/layer counts (it also leaves out the few spheres resting on nothing). The feed is every
sphere of the state. Percentiles by volume with the plugin's convention (the smallest diameter
whose cumulative d^3 share reaches p); fines are the spheres strictly below the feed's D10. Prints
the layer/feed ratios of D10, D50, D90 and the fines shares, each with the standard deviation of
400 bootstrap resamples of the layer (seed 1): the noise a single layer of that many spheres has.
"""
import random
import re
import statistics
import sys


def column(text, name):
    m = re.search(r'Name="%s"[^>]*>(.*?)</DataArray>' % name, text, re.S)
    return [float(v) for v in m.group(1).split()]


def percentile(d, p):
    d = sorted(d)
    total = sum(v**3 for v in d)
    below = 0.0
    for v in d:
        below += v**3
        if below >= p * total:
            return v
    return d[-1]


def fines(d, threshold):
    return sum(v**3 for v in d if v < threshold) / sum(v**3 for v in d)


text = open(sys.argv[1] + "/state.vtp").read()
x0, x1 = float(sys.argv[2]) * 1e-3, float(sys.argv[3]) * 1e-3
points, radius = column(text, "Points"), column(text, "radius")
x, z, d = points[0::3], points[2::3], [2 * r for r in radius]
feed = {p: percentile(d, p) for p in (0.1, 0.5, 0.9)}
layer = [di for xi, zi, di in zip(x, z, d) if x0 <= xi < x1 and zi < 2e-4]


def metrics(sample):
    return [percentile(sample, p) / feed[p] for p in (0.1, 0.5, 0.9)] + [fines(sample, feed[0.1])]


random.seed(1)
resamples = [metrics([random.choice(layer) for _ in layer]) for _ in range(400)]
print("layer %d spheres, feed %d; feed fines %.4f" % (len(layer), len(d), fines(d, feed[0.1])))
measured = metrics(layer)
for i, name in enumerate(["d10_ratio", "d50_ratio", "d90_ratio", "layer_fines"]):
    print("%-12s %.4f +- %.4f" % (name, measured[i], statistics.stdev(r[i] for r in resamples)))
