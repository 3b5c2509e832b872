#!/usr/bin/python3
"""docs/surrogates.md, "The peers' scene, measured": the multi-fidelity map against the 45-case map on
the expensive cases it never saw.

  bench/surrogates/mf_holdout.py MF_RUN FACTORIAL_RUN OUT_DIR

MF_RUN: a run of peers_multifidelity.yaml; FACTORIAL_RUN: peers_factorial.yaml's cases characterised
over the same region as MF_RUN (y = 0-1.25 mm: `spreadmap run` of the factorial file with that region
and `--only characterise` on a copy of its run). Writes three tables for `spreadmap train`:
  mf.csv           the MF run's rows (cheap and expensive, fidelity 0/1) to train, the factorial's
                   expensive cases the MF run did not use to test (split column 'set');
  factorial.csv    the 45 expensive cases (to cross-validate, --split kfold:5);
  expensive15.csv  the MF run's expensive cases alone to train, the same held-out cases to test.
Standard library only; checks that the expensive cases both runs share have the same values.
"""
import csv
import os
import sys


def rows(run_dir):
    with open(os.path.join(run_dir, "metrics.csv"), newline="") as f:
        return list(csv.DictReader(f))


def write(path, table):
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(table[0].keys()))
        w.writeheader()
        w.writerows(table)


def main():
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    mf, fac, out = rows(sys.argv[1]), rows(sys.argv[2]), sys.argv[3]
    os.makedirs(out, exist_ok=True)
    keep = ["case", "U", "omega", "vs", "rq"]
    expensive = {r["case"]: r for r in mf if r["fidelity"] == "1"}
    for r in fac:
        if r["case"] in expensive and any(expensive[r["case"]][k] != r[k] for k in ("vs", "rq")):
            sys.exit(f"{r['case']}: the two runs disagree; characterise the factorial over the MF run's region")
    held = [r for r in fac if r["case"] not in expensive]
    write(os.path.join(out, "mf.csv"),
          [{**{k: r[k] for k in keep}, "fidelity": r["fidelity"], "set": "train"} for r in mf] +
          [{**{k: r[k] for k in keep}, "fidelity": "1", "set": "test"} for r in held])
    write(os.path.join(out, "factorial.csv"), [{k: r[k] for k in keep} for r in fac])
    write(os.path.join(out, "expensive15.csv"),
          [{**{k: r[k] for k in keep}, "set": "train" if r["case"] in expensive else "test"} for r in fac])
    print(f"{len(expensive)} expensive cases in the MF run, {len(held)} held out, "
          f"{len(mf) - len(expensive)} cheap; tables in {out}")


if __name__ == "__main__":
    main()
