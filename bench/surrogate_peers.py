#!/usr/bin/python3
"""Peer surrogates on the same data and split as `spreadmap train`: scikit-learn's MLPRegressor
(the study's network shape: 1 hidden layer of 200 logistic units) and GaussianProcessRegressor
(constant x ARD RBF + white noise, one GP per output), scored like the study's Table 4:
NRMSE = 100 x RMSE / (max - min of the split's true values) [%] and Pearson R, train and test.

Input: a CSV with a header, one row per case, the input and output columns and a split column
whose values are `train` or `test` (case-insensitive), e.g. train/<model>/data.csv written by
`spreadmap train`. Column names match case-insensitively. Without a split column the rows are
split 35/10-style (test share 10/45, at least 2) by a seeded shuffle. spreadmap's own bpnn and gp
are then trained by `spreadmap train` on exactly the same rows and split (given to it as a column)
and printed beside the peers (rows sm-bpnn, sm-gp; the fit time includes the program's start).

  /usr/bin/python3 bench/surrogate_peers.py runs/quickstart/train/bpnn/data.csv \
      --inputs U,omega --outputs vs,rq --split-column split
  /usr/bin/python3 bench/surrogate_peers.py --demo     # the smooth test function on the 5 x 9 grid

Needs python3-sklearn (Debian: apt-get install -y python3-sklearn); a bench dependency only.
"""
import argparse
import csv
import json
import math
import os
import subprocess
import sys
import tempfile
import time
import warnings

import numpy as np


def read_table(path):
    with open(path, newline="") as f:
        rows = [r for r in csv.reader(f) if any(c.strip() for c in r)]
    if not rows:
        sys.exit(f"error: {path}: empty file (no header row)")
    header = [h.strip() for h in rows[0]]
    return header, rows[1:]


def column(header, name, path):
    low = [h.lower() for h in header]
    if name.lower() not in low:
        sys.exit(f"error: {path}: no column '{name}'; the columns are: {', '.join(header)}")
    return low.index(name.lower())


def numbers(rows, index, name, path):
    out = []
    for line, r in enumerate(rows, start=2):
        try:
            out.append(float(r[index]))
        except (ValueError, IndexError):
            sys.exit(f"error: {path}:{line}: column '{name}': '{r[index] if index < len(r) else ''}' is not a number")
    return np.array(out)


def nrmse(t, p):
    rng = t.max() - t.min()
    return 100.0 * math.sqrt(np.mean((t - p) ** 2)) / rng if rng > 0 else float("nan")


def pearson(a, b):
    if len(a) < 2 or np.std(a) == 0 or np.std(b) == 0:
        return float("nan")
    return float(np.corrcoef(a, b)[0, 1])


def demo_table():
    """The smooth stand-in of tests/unit/surrogate_study_function.hpp on the study's 5 x 9 grid."""
    header = ["U", "omega", "vs", "rq", "split"]
    rows = []
    for i in range(5):
        for j in range(9):
            u, w = 0.04 + 0.015 * i, -20 + 5 * j
            h = 260e-6 * (1 + 0.12 * math.tanh((w + 2) / 15)) * (1 - 0.15 * (u / 0.1) ** 2)
            s = (u - 0.04) / 0.06
            rq = 100e-6 * (0.95 + 0.06 * (1 - math.tanh((w - 3) / 10)) + 0.08 * s * s + 0.02 * math.sin((w + 5) / 7))
            rows.append([str(u), str(w), repr(u * h), repr(rq), ""])
    order = np.random.default_rng(1).permutation(len(rows))
    for k, r in enumerate(order):
        rows[r][4] = "test" if k < 10 else "train"
    return header, rows


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("csv", nargs="?", help="data CSV (e.g. train/<model>/data.csv)")
    ap.add_argument("--inputs", default="U,omega")
    ap.add_argument("--outputs", default="vs,rq")
    ap.add_argument("--split-column", default="split")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--restarts", type=int, default=5, help="GP optimiser restarts")
    ap.add_argument("--demo", action="store_true", help="use the built-in smooth test function")
    ap.add_argument("--spreadmap", default=os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "build", "bin",
                                                        "spreadmap"),
                    help="spreadmap binary whose bpnn and gp are scored beside the peers on the same split "
                         "(skipped when missing)")
    a = ap.parse_args()
    try:
        from sklearn.gaussian_process import GaussianProcessRegressor
        from sklearn.gaussian_process.kernels import RBF, ConstantKernel, WhiteKernel
        from sklearn.neural_network import MLPRegressor
        from sklearn.preprocessing import StandardScaler
    except ImportError:
        sys.exit("error: scikit-learn is missing; install it with: apt-get install -y python3-sklearn")

    if a.demo:
        path = "<demo>"
        header, rows = demo_table()
    elif a.csv:
        path = a.csv
        header, rows = read_table(path)
    else:
        ap.error("give a CSV or --demo")
    ins, outs = a.inputs.split(","), a.outputs.split(",")
    x = np.column_stack([numbers(rows, column(header, n, path), n, path) for n in ins])
    y = np.column_stack([numbers(rows, column(header, n, path), n, path) for n in outs])
    if a.split_column.lower() in [h.lower() for h in header]:
        c = column(header, a.split_column, path)
        labels = [r[c].strip().lower() for r in rows]
        bad = [(k + 2, v) for k, v in enumerate(labels) if v not in ("train", "test")]
        if bad:
            sys.exit(f"error: {path}:{bad[0][0]}: column '{a.split_column}': '{bad[0][1]}' is neither train nor test")
        train = np.array([v == "train" for v in labels])
    else:
        n_test = min(len(rows) - 2, max(2, round(len(rows) * 10 / 45)))
        train = np.ones(len(rows), bool)
        train[np.random.default_rng(a.seed).permutation(len(rows))[:n_test]] = False
    test = ~train
    print(f"{path}: {train.sum()} train / {test.sum()} test rows; inputs {ins}, outputs {outs}")

    xs = StandardScaler().fit(x[train])
    print(f"{'model':<8}{'output':<10}{'NRMSE train %':>14}{'NRMSE test %':>14}{'R train':>10}{'R test':>10}{'fit s':>8}")
    for k, name in enumerate(outs):
        ys = StandardScaler().fit(y[train, k:k + 1])
        yt = ys.transform(y[train, k:k + 1]).ravel()
        models = {
            "mlp": MLPRegressor(hidden_layer_sizes=(200,), activation="logistic", solver="lbfgs", alpha=1e-4,
                                max_iter=5000, random_state=a.seed),
            "gp": GaussianProcessRegressor(
                kernel=ConstantKernel(1.0, (1e-4, 1e4)) * RBF(np.ones(x.shape[1]), (1e-2, 1e3))
                + WhiteKernel(1e-6, (1e-12, 1.0)), n_restarts_optimizer=a.restarts, random_state=a.seed),
        }
        for label, m in models.items():
            t0 = time.perf_counter()
            with warnings.catch_warnings(record=True) as caught:
                warnings.simplefilter("always")
                m.fit(xs.transform(x[train]), yt)
            dt = time.perf_counter() - t0
            note = "  (sklearn warned: not converged)" if any("converge" in str(w.message).lower() or
                                                           "lnsrch" in str(w.message).lower() for w in caught) else ""
            p = ys.inverse_transform(m.predict(xs.transform(x)).reshape(-1, 1)).ravel()
            t = y[:, k]
            print(f"{label:<8}{name:<10}{nrmse(t[train], p[train]):>14.3f}{nrmse(t[test], p[test]):>14.3f}"
                  f"{pearson(t[train], p[train]):>10.5f}{pearson(t[test], p[test]):>10.5f}{dt:>8.2f}{note}")
    spreadmap_scores(a.spreadmap, ins, outs, x, y, train)


def spreadmap_scores(binary, ins, outs, x, y, train):
    """`spreadmap train` with the same rows and the same split (given as a column), both models."""
    if not os.access(binary, os.X_OK):
        print(f"spreadmap: {binary} not found or not executable: build it, or pass --spreadmap BIN")
        return
    with tempfile.TemporaryDirectory() as work:
        data = os.path.join(work, "data.csv")
        with open(data, "w", newline="") as f:
            w = csv.writer(f)
            w.writerow(ins + outs + ["split"])
            for k in range(len(x)):
                w.writerow([repr(float(v)) for v in x[k]] + [repr(float(v)) for v in y[k]] +
                           ["train" if train[k] else "test"])
        # the gp as scikit-learn's: the plain marginal likelihood, without spreadmap's noise prior
        same_setting = {"bpnn": [], "gp": ["--param", "noise_prior_width=0"]}
        for model in ("bpnn", "gp"):
            t0 = time.perf_counter()
            run = subprocess.run([binary, "train", data, "--inputs", ",".join(ins), "--outputs", ",".join(outs),
                                  "--model", model, "--split-column", "split", "--format", "json", "--no-figures",
                                  "--quiet", "--out", os.path.join(work, model)] + same_setting[model],
                                 capture_output=True, text=True)
            dt = time.perf_counter() - t0
            if run.returncode != 0:
                print(f"spreadmap {model}: failed ({run.returncode}): {run.stderr.strip()}")
                continue
            report = json.loads(run.stdout)
            for name in outs:
                o = report["outputs"][name]
                print(f"{'sm-' + model:<8}{name:<10}{o['nrmse_train']:>14.3f}{o['nrmse_test']:>14.3f}"
                      f"{o['r_train']:>10.5f}{o['r_test']:>10.5f}{dt:>8.2f}")


if __name__ == "__main__":
    main()
