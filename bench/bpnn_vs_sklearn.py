#!/usr/bin/python3
"""spreadmap's bpnn beside scikit-learn's MLPRegressor on the study's layout, one setting changed at a time.

Data: the smooth stand-in of tests/unit/surrogate_study_function.hpp on the study's 5 x 9 grid
(surrogate_peers.py's demo table), each value multiplied by (1 + noise * N(0, 1)) -- the heap-to-heap
scatter of DEM runs is 1-2 % -- for --sets independent noise draws (numpy seeds 1..sets). Split: the
study's 35/10 holdout as `spreadmap train --split holdout --seed 1` draws it, the same rows for every
model. Network: 1 hidden layer of 200 logistic units, linear output, L-BFGS, inputs and outputs
standardised on the training rows. Scores: test NRMSE = 100 x RMSE / range of the test values [%].

Each row prints the mean test NRMSE of V_s and R_q over the sets and seeds (+- the standard error of
the mean) and mean paired differences [% points] (same set, same seed) to row 1 (scikit-learn as
surrogate_peers.py runs it) and to row 4 (bpnn's defaults) +- their standard errors:
a difference within about two standard errors is within noise.

  /usr/bin/python3 bench/bpnn_vs_sklearn.py                     # 1.5 % noise, 10 sets
  /usr/bin/python3 bench/bpnn_vs_sklearn.py --noise 0 --seeds 4 # noiseless, 4 initial-weight seeds

Needs python3-sklearn (Debian: apt-get install -y python3-sklearn) and a built spreadmap.
"""
import argparse
import csv
import json
import math
import os
import subprocess
import sys
import tempfile
import warnings

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from surrogate_peers import demo_table, nrmse  # noqa: E402  (the same data source and score)

OUTS = ["vs", "rq"]


def study_table():
    """(U, omega) rows and the noiseless (vs, rq) of the study's 45 cases."""
    header, rows = demo_table()
    x = np.array([[float(r[0]), float(r[1])] for r in rows])
    y = np.array([[float(r[2]), float(r[3])] for r in rows])
    return x, y


def write_csv(path, x, y, train=None):
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["U", "omega"] + OUTS + (["split"] if train is not None else []))
        for k in range(len(x)):
            w.writerow([repr(float(v)) for v in x[k]] + [repr(float(v)) for v in y[k]] +
                       (["train" if train[k] else "test"] if train is not None else []))


def spreadmap_split(binary, x, y, work):
    """The study's holdout as spreadmap train draws it (seed 1): a boolean mask of training rows."""
    data = os.path.join(work, "split.csv")
    write_csv(data, x, y)
    out = os.path.join(work, "split")
    run = subprocess.run([binary, "train", data, "--inputs", "U,omega", "--outputs", ",".join(OUTS), "--model", "gp",
                          "--split", "holdout", "--seed", "1", "--no-figures", "--quiet", "--out", out],
                         capture_output=True, text=True)
    if run.returncode != 0:
        sys.exit(f"error: spreadmap train (for the split) failed: {run.stderr.strip()}")
    with open(os.path.join(out, "data.csv"), newline="") as f:
        labels = [r["split"] for r in csv.DictReader(f)]
    return np.array([v == "train" for v in labels])


def sklearn_scores(x, y, train, joint=False, **options):
    """Test NRMSE per output of MLPRegressor: one network per output, or one for both (joint)."""
    from sklearn.neural_network import MLPRegressor
    from sklearn.preprocessing import StandardScaler
    xs = StandardScaler().fit(x[train])
    groups = [[0, 1]] if joint else [[0], [1]]
    scores = [0.0, 0.0]
    for g in groups:
        ys = StandardScaler().fit(y[train][:, g])
        args = dict(hidden_layer_sizes=(200,), activation="logistic", solver="lbfgs", alpha=1e-4, max_iter=5000,
                    random_state=1)
        args.update(options)
        m = MLPRegressor(**args)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # "not converged" is the point of some rows
            m.fit(xs.transform(x[train]), ys.transform(y[train][:, g]).squeeze())
        p = ys.inverse_transform(m.predict(xs.transform(x)).reshape(len(x), -1))
        for j, k in enumerate(g):
            scores[k] = nrmse(y[~train, k], p[~train, j])
    return scores


def spreadmap_scores(binary, x, y, train, params, work):
    """Test NRMSE per output of `spreadmap train --model bpnn` with these parameters, same rows and split."""
    data = os.path.join(work, "data.csv")
    write_csv(data, x, y, train)
    cmd = [binary, "train", data, "--inputs", "U,omega", "--outputs", ",".join(OUTS), "--model", "bpnn",
           "--split-column", "split", "--format", "json", "--no-figures", "--quiet", "--out", os.path.join(work, "bpnn")]
    for p in params:
        cmd += ["--param", p]
    run = subprocess.run(cmd, capture_output=True, text=True)
    if run.returncode != 0:
        sys.exit(f"error: spreadmap train {' '.join(params)} failed: {run.stderr.strip()}")
    outputs = json.loads(run.stdout)["outputs"]
    return [outputs[k]["nrmse_test"] for k in OUTS]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--noise", type=float, default=0.015, help="relative noise on every value (0.015 = 1.5 %%)")
    ap.add_argument("--sets", type=int, default=10, help="independent noise draws (ignored without noise)")
    ap.add_argument("--seeds", type=int, default=1, help="initial-weight seeds per set (both libraries: 1..seeds)")
    ap.add_argument("--spreadmap", default=os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "build", "bin",
                                                        "spreadmap"))
    a = ap.parse_args()
    if not os.access(a.spreadmap, os.X_OK):
        sys.exit(f"error: {a.spreadmap} not found or not executable: build it, or pass --spreadmap BIN")
    try:
        import sklearn  # noqa: F401
    except ImportError:
        sys.exit("error: scikit-learn is missing; install it with: apt-get install -y python3-sklearn")

    alpha_over_n = 1e-4 / 35  # scikit-learn's L2 term: alpha / (2 n_samples) ||W||^2 beside (1/2) mse
    rows = [
        ("scikit-learn MLP, one per output (surrogate_peers.py: alpha 1e-4, tol 1e-4)", "sk", {}),
        ("scikit-learn MLP, one per output, run to convergence (tol 1e-12)", "sk", {"tol": 1e-12, "max_fun": 10**6}),
        ("scikit-learn MLP, one network for both outputs", "sk", {"joint": True}),
        ("bpnn defaults: one network, no early stopping (the study's network)", "sm", []),
        ("bpnn one network + 5 stopping folds (stopping_folds=5)", "sm", ["stopping_folds=5"]),
        ("bpnn one per output, no early stopping (networks=per_output)", "sm", ["networks=per_output"]),
        ("bpnn one per output, scikit-learn's objective (networks=per_output regularisation=sum lambda=alpha/n)",
         "sm", ["networks=per_output", "regularisation=sum", f"lambda={alpha_over_n!r}"]),
        ("bpnn one per output + 5 stopping folds (networks=per_output stopping_folds=5)", "sm",
         ["networks=per_output", "stopping_folds=5"]),
    ]
    x, y0 = study_table()
    sets = range(1, a.sets + 1) if a.noise > 0 else [0]
    results = {label: [] for label, _, _ in rows}
    with tempfile.TemporaryDirectory() as work:
        train = spreadmap_split(a.spreadmap, x, y0, work)
        print(f"{int(train.sum())} train / {int((~train).sum())} test rows (spreadmap's holdout, seed 1); "
              f"noise {100 * a.noise:g} %, sets {list(sets)}, initial-weight seeds 1..{a.seeds}", flush=True)
        for s in sets:
            y = y0 * (1 + a.noise * np.random.default_rng(s).normal(size=y0.shape)) if a.noise > 0 else y0
            for seed in range(1, a.seeds + 1):
                for label, kind, setting in rows:
                    if kind == "sk":
                        score = sklearn_scores(x, y, train, random_state=seed, **setting)
                    else:
                        score = spreadmap_scores(a.spreadmap, x, y, train, setting + [f"seed={seed}"], work)
                    results[label].append(score)

    def mean_se(v):
        v = np.asarray(v)
        return v.mean(), (v.std(ddof=1) / math.sqrt(len(v)) if len(v) > 1 else float("nan"))

    base, before = np.array(results[rows[0][0]]), np.array(results[rows[3][0]])
    print("\n| setting | V_s test NRMSE [%] | R_q test NRMSE [%] | V_s minus row 1 | V_s minus row 4 | R_q minus row 4 |")
    print("|---|---|---|---|---|---|")
    for n, (label, _, _) in enumerate(rows, start=1):
        r = np.array(results[label])
        cells = [mean_se(r[:, 0]), mean_se(r[:, 1]), mean_se(r[:, 0] - base[:, 0]), mean_se(r[:, 0] - before[:, 0]),
                 mean_se(r[:, 1] - before[:, 1])]
        print(f"| {n}. {label} | " + " | ".join(
            f"{m:{'+' if k >= 2 else ''}.3f} ± {e:.3f}" for k, (m, e) in enumerate(cells)) + " |")
    ratio = before[:, 0] / base[:, 0]
    print(f"\nrow 4 / row 1, V_s test NRMSE of each set: {' '.join(f'{v:.2f}' for v in ratio)}")

if __name__ == "__main__":
    main()
