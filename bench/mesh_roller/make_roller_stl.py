#!/usr/bin/python3
"""Writes the peers' roller as a binary STL: a cylinder of diameter 10 mm and length 70 mm about the
y axis through the origin, its circle a regular polygon of N sides with a corner at the bottom (so
its lowest point, and the gap, are exact). Units: mm. Usage: make_roller_stl.py N OUT.stl"""
import math
import struct
import sys

n, out = int(sys.argv[1]), sys.argv[2]
R, y0, y1 = 5.0, -35.0, 35.0
ring = [(R * math.sin(2 * math.pi * k / n), -R * math.cos(2 * math.pi * k / n)) for k in range(n)]  # (x, z), counter-clockwise: its cap at y0 faces -y
tris = []
for k in range(n):
    (ax, az), (bx, bz) = ring[k], ring[(k + 1) % n]
    a, b, c, d = (ax, y0, az), (bx, y0, bz), (bx, y1, bz), (ax, y1, az)
    tris += [(a, c, b), (a, d, c)]
for k in range(1, n - 1):
    p, q, r = ring[0], ring[k], ring[k + 1]
    tris.append(((p[0], y0, p[1]), (q[0], y0, q[1]), (r[0], y0, r[1])))
    tris.append(((p[0], y1, p[1]), (r[0], y1, r[1]), (q[0], y1, q[1])))
with open(out, "wb") as f:
    f.write(b"peers' roller, D 10 mm, L 70 mm, mm".ljust(80, b" "))
    f.write(struct.pack("<I", len(tris)))
    for t in tris:
        f.write(struct.pack("<3f", 0, 0, 0))
        for p in t:
            f.write(struct.pack("<3f", *p))
        f.write(struct.pack("<H", 0))
