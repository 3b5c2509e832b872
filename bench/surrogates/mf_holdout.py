#!/usr/bin/python3
"""docs/surrogates.md, "The peers' scene, measured": the multi-fidelity map against the 45-case map on
the expensive cases it never saw, both judged on the same cases with the same normaliser.

  bench/surrogates/mf_holdout.py MF_RUN FACTORIAL_RUN OUT_DIR [SPREADMAP]

MF_RUN: a run of peers_multifidelity.yaml; FACTORIAL_RUN: a run of peers_factorial.yaml (the same
region: every expensive case across its full 2.5 mm; the script checks that the cases both runs hold
have the same values). SPREADMAP: the binary (default build/bin/spreadmap). Writes to OUT_DIR:
  mf.csv           the MF run's rows (cheap and expensive, fidelity 0/1) to train, the factorial's
                   expensive cases the MF run did not use to test (column 'set');
  factorial.csv    the 45 expensive cases;
  expensive.csv    the MF run's expensive cases alone to train, the same held-out cases to test;
and trains with `spreadmap train` (gp): the factorial 5-fold cross-validated (the 45-case map's
figure), the MF rows with one noise per fidelity and with one shared noise, the expensive cases
alone. Then the paired figure: on the held-out cases, the 45-case map's out-of-fold predictions
(its cv.csv) against the MF map's predictions (query's 4 digits), one NRMSE each over the same cases
(RMSE / their range), and a bootstrap interval of their difference.
Standard library only.
"""
import csv
import json
import math
import os
import random
import subprocess
import sys

OUTPUTS = ("vs", "rq")


def rows(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def write(path, table):
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(table[0].keys()))
        w.writeheader()
        w.writerows(table)


def train(spreadmap, table, out, inputs, split, params=()):
    cmd = [spreadmap, "train", table, "--inputs", inputs, "--model", "gp", "--split", split, "--out", out,
           "--no-figures", "--format", "json", "-q"]
    for p in params:
        cmd += ["--param", p]
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
    with open(os.path.join(out, "report.json")) as f:
        return json.load(f)


SI = {"mm^2/s": 1e-6, "um": 1e-6, "m^2/s": 1.0, "m": 1.0}


def predict(spreadmap, model, setting):
    """The model's mean at one setting, per output, in SI units (query prints `vs 11.04 mm^2/s +- ...`)."""
    at = ",".join(f"{k}={v}" for k, v in setting.items())
    out = subprocess.run([spreadmap, "query", model, "--at", at, "-q"], check=True, capture_output=True,
                         text=True).stdout
    means = {}
    for line in out.splitlines():
        name, value, unit = line.split()[:3]
        means[name] = float(value) * SI[unit]
    return means


def nrmse(true, pred):
    rmse = math.sqrt(sum((t - p) ** 2 for t, p in zip(true, pred)) / len(true))
    return 100 * rmse / (max(true) - min(true))


def output(report, name):
    return next(o for o in report["outputs"] if o["name"] == name)


def main():
    if len(sys.argv) not in (4, 5):
        sys.exit(__doc__)
    mf_run, fac_run, out = sys.argv[1:4]
    spreadmap = sys.argv[4] if len(sys.argv) == 5 else "build/bin/spreadmap"
    mf, fac = rows(os.path.join(mf_run, "metrics.csv")), rows(os.path.join(fac_run, "metrics.csv"))
    os.makedirs(out, exist_ok=True)
    keep = ["case", "U", "omega", "vs", "rq"]
    expensive = {r["case"]: r for r in mf if r["fidelity"] == "1"}
    for r in fac:
        if r["case"] in expensive and any(expensive[r["case"]][k] != r[k] for k in OUTPUTS):
            sys.exit(f"{r['case']}: the two runs disagree; characterise both over the same region")
    held = [r for r in fac if r["case"] not in expensive]
    p = lambda name: os.path.join(out, name)
    write(p("mf.csv"), [{**{k: r[k] for k in keep}, "fidelity": r["fidelity"], "set": "train"} for r in mf] +
          [{**{k: r[k] for k in keep}, "fidelity": "1", "set": "test"} for r in held])
    write(p("factorial.csv"), [{k: r[k] for k in keep} for r in fac])
    write(p("expensive.csv"),
          [{**{k: r[k] for k in keep}, "set": "train" if r["case"] in expensive else "test"} for r in fac])
    print(f"{len(expensive)} expensive cases in the MF run, {len(held)} held out, "
          f"{len(mf) - len(expensive)} cheap; tables in {out}")

    full = train(spreadmap, p("factorial.csv"), p("gp_factorial"), "U,omega", "kfold:5")
    mf_grouped = train(spreadmap, p("mf.csv"), p("gp_mf"), "U,omega,fidelity", "column:set", ["noise_by_input=3"])
    mf_shared = train(spreadmap, p("mf.csv"), p("gp_mf_shared"), "U,omega,fidelity", "column:set")
    alone = train(spreadmap, p("expensive.csv"), p("gp_expensive"), "U,omega", "column:set")

    # the paired figure: the same held-out cases, the same normaliser
    cv = {r["case"]: r for r in rows(p("gp_factorial/cv.csv"))}
    held_ids = [r["case"] for r in held]
    mf_pred = {c: predict(spreadmap, p("gp_mf/model.json"),
                          {"U": f"{float(r['U']) * 1e3}mm/s", "omega": f"{r['omega']}rad/s", "fidelity": "1"})
               for c, r in ((r["case"], r) for r in held)}

    print(f"\nNRMSE [%]               {'V_s':>16} {'R_q':>16}")
    line = lambda label, a, b: print(f"{label:<24}{a:>16} {b:>16}")
    line("45 cases, 5-fold CV", *(f"{output(full, o)['nrmse_cv']:.2f} +- {output(full, o)['nrmse_cv_sd']:.2f}"
                                  for o in OUTPUTS))
    line("MF, noise per fidelity", *(f"{output(mf_grouped, o)['nrmse_test']:.2f}" for o in OUTPUTS))
    line("MF, one shared noise", *(f"{output(mf_shared, o)['nrmse_test']:.2f}" for o in OUTPUTS))
    line(f"{len(expensive)} expensive alone", *(f"{output(alone, o)['nrmse_test']:.2f}" for o in OUTPUTS))
    print(f"\npaired, on the {len(held_ids)} held-out cases (RMSE / their range):")
    for o in OUTPUTS:
        true = [float(cv[c][o + "_true"]) for c in held_ids]
        a = [float(cv[c][o + "_cv"]) for c in held_ids]
        b = [mf_pred[c][o] for c in held_ids]
        # the difference's scatter: the held-out cases resampled with replacement (seeded)
        rng, diffs = random.Random(1), []
        for _ in range(2000):
            pick = [rng.randrange(len(true)) for _ in true]
            t = [true[i] for i in pick]
            if max(t) > min(t):
                diffs.append(nrmse(t, [b[i] for i in pick]) - nrmse(t, [a[i] for i in pick]))
        diffs.sort()
        lo, hi = diffs[int(0.16 * len(diffs))], diffs[int(0.84 * len(diffs))]
        print(f"  {o}: 45-case map out-of-fold {nrmse(true, a):.2f} %, MF map {nrmse(true, b):.2f} % "
              f"(MF - 45-case: {nrmse(true, b) - nrmse(true, a):+.2f}, 68 % bootstrap interval {lo:+.2f} to {hi:+.2f})")


if __name__ == "__main__":
    main()
