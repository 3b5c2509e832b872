// A small limited-memory BFGS minimiser with box bounds by projection, shared by the surrogate
// plugins (bpnn weights, gp log-hyperparameters). Header-only so each plugin stays self-contained.
//
// Method: two-loop recursion (Nocedal & Wright 2006, Alg. 7.4) for the direction, backtracking
// Armijo line search, projection onto [lower, upper] after every trial step; the gradient of a
// component held at a bound and pointing outwards is zeroed (projected gradient). Curvature pairs
// with s.y <= 1e-12 |s||y| are skipped so the inverse-Hessian estimate stays positive definite.
// Deterministic: no randomness, no threads.
#pragma once
#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <deque>
#include <functional>
#include <limits>
#include <vector>

namespace spreadmap::surrogate {

// on_iteration(iteration, x, value) after each accepted step; returning false stops the search.
// f(x, grad) returns the objective and writes its gradient into grad (same size as x).
using Objective = std::function<double(const Eigen::VectorXd &, Eigen::VectorXd &)>;

struct LbfgsOptions {
  long max_iterations = 1000;
  int memory = 10;
  double gradient_tolerance = 1e-8;   // stop when max |projected gradient| falls below this
  double relative_tolerance = 1e-14;  // stop when the objective changes by less than this (relative)
  Eigen::VectorXd lower, upper;       // empty = unbounded
};

struct LbfgsResult {
  double value = 0;
  long iterations = 0;
  bool converged = false;
};

namespace detail {
inline void project(Eigen::VectorXd &x, const LbfgsOptions &o) {
  if (o.lower.size() == x.size()) x = x.cwiseMax(o.lower);
  if (o.upper.size() == x.size()) x = x.cwiseMin(o.upper);
}
// Zero the gradient components that would push x out of the box (they cannot move).
inline Eigen::VectorXd projected_gradient(const Eigen::VectorXd &x, Eigen::VectorXd g, const LbfgsOptions &o) {
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    if (o.lower.size() == x.size() && x[i] <= o.lower[i] && g[i] > 0) g[i] = 0;
    if (o.upper.size() == x.size() && x[i] >= o.upper[i] && g[i] < 0) g[i] = 0;
  }
  return g;
}
}  // namespace detail

// Minimises f from x (updated in place). A non-finite objective at a trial point is treated as
// "too far" and the step is halved.
inline LbfgsResult lbfgs_minimise(const Objective &f, Eigen::VectorXd &x, const LbfgsOptions &o,
                                  const std::function<bool(long, const Eigen::VectorXd &, double)> &on_iteration = {}) {
  detail::project(x, o);
  Eigen::VectorXd g(x.size());
  double fx = f(x, g);
  LbfgsResult r;
  std::deque<Eigen::VectorXd> s_hist, y_hist;
  std::deque<double> rho_hist;
  for (r.iterations = 0; r.iterations < o.max_iterations; ++r.iterations) {
    const Eigen::VectorXd pg = detail::projected_gradient(x, g, o);
    if (!std::isfinite(fx)) break;
    if (pg.lpNorm<Eigen::Infinity>() < o.gradient_tolerance) {
      r.converged = true;
      break;
    }
    // Two-loop recursion on the projected gradient.
    Eigen::VectorXd q = pg;
    std::vector<double> a(s_hist.size());
    for (int i = static_cast<int>(s_hist.size()) - 1; i >= 0; --i) {
      a[i] = rho_hist[i] * s_hist[i].dot(q);
      q -= a[i] * y_hist[i];
    }
    double gamma = 1.0;
    if (!s_hist.empty()) gamma = s_hist.back().dot(y_hist.back()) / y_hist.back().squaredNorm();
    else gamma = 1.0 / std::max(1.0, pg.norm());  // first step: unit length along -g
    Eigen::VectorXd d = gamma * q;
    for (std::size_t i = 0; i < s_hist.size(); ++i) {
      const double b = rho_hist[i] * y_hist[i].dot(d);
      d += (a[i] - b) * s_hist[i];
    }
    d = -d;
    if (d.dot(pg) >= 0) {  // not a descent direction: restart from steepest descent
      s_hist.clear(), y_hist.clear(), rho_hist.clear();
      d = -pg / std::max(1.0, pg.norm());
    }
    // Backtracking Armijo search along the projected path.
    double step = 1.0, f_new = fx;
    Eigen::VectorXd x_new, g_new(x.size());
    bool accepted = false;
    for (int k = 0; k < 60; ++k, step *= 0.5) {
      x_new = x + step * d;
      detail::project(x_new, o);
      f_new = f(x_new, g_new);
      if (std::isfinite(f_new) && f_new <= fx + 1e-4 * pg.dot(x_new - x)) {
        accepted = true;
        break;
      }
    }
    if (!accepted) {
      if (s_hist.empty()) break;  // even steepest descent fails: at a minimum to round-off
      s_hist.clear(), y_hist.clear(), rho_hist.clear();
      continue;
    }
    const Eigen::VectorXd s = x_new - x, y = g_new - g;
    const double change = std::abs(fx - f_new);
    x = x_new, g = g_new;
    const double f_old = fx;
    fx = f_new;
    if (s.dot(y) > 1e-12 * s.norm() * y.norm()) {
      s_hist.push_back(s), y_hist.push_back(y), rho_hist.push_back(1.0 / s.dot(y));
      if (static_cast<int>(s_hist.size()) > o.memory) s_hist.pop_front(), y_hist.pop_front(), rho_hist.pop_front();
    }
    if (on_iteration && !on_iteration(r.iterations + 1, x, fx)) {
      ++r.iterations;
      break;
    }
    if (change <= o.relative_tolerance * std::max({1.0, std::abs(f_old), std::abs(fx)})) {
      ++r.iterations;
      r.converged = true;
      break;
    }
  }
  r.value = fx;
  return r;
}

}  // namespace spreadmap::surrogate
