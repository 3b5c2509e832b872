#!/usr/bin/python3
"""Tables and figures of docs/powders.md's cohesion and multi-layer study, from the run directories
of bench/powders/bond_study.yaml and layers_study.yaml (standard library only: the figures are SVG).

usage: bench/powders/study_figures.py BOND_RUN LAYERS_RUN OUT_DIR
"""
import csv
import math
import sys
from pathlib import Path

WEIGHT = 4430 * 9.81 * math.pi / 6 * 250e-6**3  # N, one 250 um Ti-6Al-4V sphere
R_STAR = 62.5e-6  # m, two equal 250 um spheres


def bond(gamma):
    """Bond number of the DMT pull-off of two spheres over one sphere's weight."""
    return 2 * math.pi * gamma * R_STAR / WEIGHT


def rows(run):
    with open(Path(run) / "metrics.csv") as f:
        return list(csv.DictReader(f))


def num(row, key, scale=1.0):
    v = row.get(key, "")
    return float(v) * scale if v not in ("", None) else float("nan")


def mean_sd(values):
    v = [x for x in values if not math.isnan(x)]
    if not v:
        return float("nan"), float("nan")
    m = sum(v) / len(v)
    sd = math.sqrt(sum((x - m) ** 2 for x in v) / (len(v) - 1)) if len(v) > 1 else float("nan")
    return m, sd


def svg_plot(path, title, xlabel, series, ylabel, xlog=False):
    """series: list of (name, [(x, y, yerr)]) drawn as markers and lines with error bars."""
    W, H, L, R, T, B = 560, 360, 70, 20, 40, 50
    pts = [p for _, s in series for p in s if not math.isnan(p[1])]
    xs = [math.log10(p[0]) if xlog else p[0] for p in pts]
    lo = [p[1] - (0 if math.isnan(p[2]) else p[2]) for p in pts]
    hi = [p[1] + (0 if math.isnan(p[2]) else p[2]) for p in pts]
    x0, x1 = min(xs), max(xs)
    y0, y1 = min(lo), max(hi)
    pad = 0.08 * (y1 - y0 or 1)
    y0, y1 = y0 - pad, y1 + pad
    padx = 0.05 * (x1 - x0 or 1)
    x0, x1 = x0 - padx, x1 + padx

    def X(x):
        return L + (W - L - R) * ((math.log10(x) if xlog else x) - x0) / (x1 - x0)

    def Y(y):
        return H - B - (H - T - B) * (y - y0) / (y1 - y0)

    colours = ["#1f77b4", "#d62728", "#2ca02c", "#9467bd"]
    out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{W}" height="{H}" font-family="sans-serif" font-size="12">',
           f'<rect width="{W}" height="{H}" fill="white"/>',
           f'<text x="{W/2}" y="22" text-anchor="middle" font-size="14">{title}</text>',
           f'<line x1="{L}" y1="{H-B}" x2="{W-R}" y2="{H-B}" stroke="black"/>',
           f'<line x1="{L}" y1="{T}" x2="{L}" y2="{H-B}" stroke="black"/>',
           f'<text x="{(L+W-R)/2}" y="{H-12}" text-anchor="middle">{xlabel}</text>',
           f'<text x="16" y="{(T+H-B)/2}" text-anchor="middle" transform="rotate(-90 16 {(T+H-B)/2})">{ylabel}</text>']
    for k in range(5):
        y = y0 + (y1 - y0) * k / 4
        out.append(f'<text x="{L-6}" y="{Y(y)+4}" text-anchor="end">{y:.3g}</text>')
        out.append(f'<line x1="{L-3}" y1="{Y(y)}" x2="{L}" y2="{Y(y)}" stroke="black"/>')
    ticks = sorted({p[0] for p in pts})
    ticks = ticks[:: math.ceil(len(ticks) / 8)]  # at most 8 labels
    for t in ticks:
        out.append(f'<text x="{X(t)}" y="{H-B+16}" text-anchor="middle">{t:g}</text>')
    for i, (name, s) in enumerate(series):
        c = colours[i % len(colours)]
        s = [p for p in s if not math.isnan(p[1])]
        out.append('<polyline fill="none" stroke="{}" points="{}"/>'.format(
            c, " ".join(f"{X(x):.1f},{Y(y):.1f}" for x, y, _ in s)))
        for x, y, e in s:
            out.append(f'<circle cx="{X(x):.1f}" cy="{Y(y):.1f}" r="4" fill="{c}"/>')
            if not math.isnan(e):
                out.append(f'<line x1="{X(x):.1f}" y1="{Y(y-e):.1f}" x2="{X(x):.1f}" y2="{Y(y+e):.1f}" stroke="{c}"/>')
        out.append(f'<text x="{W-R-150}" y="{T+16*(i+1)}" fill="{c}">{name}</text>')
    out.append("</svg>")
    Path(path).write_text("\n".join(out) + "\n")


def bond_study(run, out):
    by_level = {}
    for r in rows(run):
        by_level.setdefault(float(r["contact.surface_energy"]), []).append(r)
    metrics = [("rq", 1e6, "R_q [um]"), ("coverage", 1, "coverage [-]"),
               ("largest_bare_patch", 1e6, "largest bare patch [mm^2]"),
               ("packing_fraction", 1, "packing [-]"), ("vs", 1e6, "V_s [mm^2/s]")]
    print("| gamma [mJ/m^2] | Bo | runs | " + " | ".join(m[2] for m in metrics) + " |")
    print("|" + "---|" * (3 + len(metrics)))
    table = {}
    for g in sorted(by_level):
        cells = []
        for key, scale, _ in metrics:
            m, sd = mean_sd([num(r, key, scale) for r in by_level[g]])
            table.setdefault(key, []).append((bond(g), m, sd))
            cells.append(f"{m:.4g} ± {sd:.2g}" if not math.isnan(sd) else f"{m:.4g}")
        print(f"| {g*1e3:g} | {bond(g):.3g} | {len(by_level[g])} | " + " | ".join(cells) + " |")
    # Bo = 0 cannot sit on a log axis: the figures put it at Bo = 0.1 and say so
    for key, scale, label in metrics[:4]:
        pts = [(max(b, 0.1), m, sd) for b, m, sd in table[key]]
        svg_plot(Path(out) / f"bond_{key}.svg", f"{label} against the Bond number (Bo = 0 drawn at 0.1)",
                 "Bo = F_pull-off / m g", [("peers' scene, mean ± sd over heaps", pts)], label, xlog=True)


def layers_study(run, out):
    by_case = {}
    for r in rows(run):
        by_case.setdefault(float(r["contact.surface_energy"]), []).append(r)
    keys = [("rq", 1e6, "R_q [um]"), ("coverage", 1, "coverage"), ("packing_top", 1, "packing, top 250 um"),
            ("packing_bulk", 1, "packing below it"), ("mean_height", 1e6, "mean height [um]"),
            ("layer_height", 1e6, "layer height [um]"), ("effective_thickness", 1e6, "effective thickness [um]"),
            ("deposited_thickness", 1e6, "deposited solid [um]"), ("largest_bare_patch", 1e6, "largest bare patch [mm^2]")]
    print("| Bo | layer | " + " | ".join(k[2] for k in keys) + " |")
    print("|" + "---|" * (2 + len(keys)))
    series = {k: [] for k, _, _ in keys}
    for g in sorted(by_case):
        for r in sorted(by_case[g], key=lambda r: int(r["layer"])):
            print(f"| {bond(g):.3g} | {r['layer']} | " + " | ".join(f"{num(r, k, s):.4g}" for k, s, _ in keys) + " |")
        for k, s, _ in keys:
            series[k].append((f"Bo = {bond(g):.3g}",
                              [(int(r["layer"]), num(r, k, s), float("nan")) for r in by_case[g]]))
    for k, _, label in keys[:4] + keys[6:8]:
        svg_plot(Path(out) / f"layers_{k}.svg", f"{label} after each layer", "layer", series[k], label)


def depth_profiles(run, out):
    """Packing against height of the bed after layers 1, 3 and 5 of case c000 (metrics.json profiles)."""
    import json
    series = []
    for k in (1, 3, 5):
        f = Path(run) / "cases" / "c000" / f"layer_{k}" / "metrics.json"
        if not f.exists():
            continue
        p = json.loads(f.read_text())["profiles"]
        series.append((f"after layer {k}", [(z * 1e6, phi, float("nan")) for z, phi in zip(p["z"], p["packing"])]))
    if series:
        svg_plot(Path(out) / "layers_depth_profile.svg", "solid fraction of 50 um slices against height",
                 "slice centre above the plate [um]", series, "solid fraction [-]")


if __name__ == "__main__":
    bond_run, layers_run, out = sys.argv[1:4]
    Path(out).mkdir(parents=True, exist_ok=True)
    if (Path(bond_run) / "metrics.csv").exists():
        bond_study(bond_run, out)
    print()
    if (Path(layers_run) / "metrics.csv").exists():
        layers_study(layers_run, out)
        depth_profiles(layers_run, out)
