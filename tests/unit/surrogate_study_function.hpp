// A smooth analytic stand-in for the study's response surfaces, used by the surrogate tests.
// Inputs: roller speed U [m/s] in [0.04, 0.10], rotation omega [rad/s] in [-20, 20].
//   V_s(U, omega) = U * h,  h = 260 um * (1 + 0.12 tanh((omega + 2) / 15)) * (1 - 0.15 (U / 0.1 m/s)^2)
//                  -> rises with U (h thins slowly), a mild omega effect;            ~1e-5 m^2/s
//   R_q(U, omega) = 100 um * (0.95 + 0.06 (1 - tanh((omega - 3) / 10)) + 0.08 ((U - 0.04) / 0.06)^2
//                            + 0.02 sin((omega + 5) / 7))
//                  -> varies mostly with omega (rougher under counter-rotation), grows with U.
// The shifts in omega keep the functions from being odd about omega = 0, which a symmetric 3-point
// design would alias to a straight line.
// The study's design: U = 40..100 mm/s step 15 (5 levels) x omega = -20..20 rad/s step 5 (9 levels).
#pragma once
#include <Eigen/Dense>

#include <spreadmap/random.hpp>

#include <cmath>
#include <cstdint>

namespace spreadmap::test {

inline double study_vs(double u, double omega) {
  const double h = 260e-6 * (1 + 0.12 * std::tanh((omega + 2) / 15)) * (1 - 0.15 * (u / 0.1) * (u / 0.1));
  return u * h;
}
inline double study_rq(double u, double omega) {
  const double s = (u - 0.04) / 0.06;
  return 100e-6 * (0.95 + 0.06 * (1 - std::tanh((omega - 3) / 10)) + 0.08 * s * s + 0.02 * std::sin((omega + 5) / 7));
}

// Rows of (U, omega) of an nu x nw full-factorial grid over the study's box, U varying slowest.
inline Eigen::MatrixXd study_grid(int nu = 5, int nw = 9) {
  Eigen::MatrixXd x(nu * nw, 2);
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nw; ++j) {
      x(i * nw + j, 0) = 0.04 + 0.06 * i / (nu - 1);
      x(i * nw + j, 1) = -20 + 40.0 * j / (nw - 1);
    }
  return x;
}
inline Eigen::MatrixXd study_outputs(const Eigen::MatrixXd &x) {
  Eigen::MatrixXd y(x.rows(), 2);
  for (Eigen::Index r = 0; r < x.rows(); ++r)
    y(r, 0) = study_vs(x(r, 0), x(r, 1)), y(r, 1) = study_rq(x(r, 0), x(r, 1));
  return y;
}

// Rows of the R_q stand-in at seeded uniform (U, omega) plus Gaussian noise of known sigma [m]: the
// situation of DEM results, whose random heaps scatter by 1-2 % between runs.
struct NoisySet {
  Eigen::MatrixXd x, y, truth;  // truth: the noiseless values
};
inline NoisySet noisy_rq(int rows, double sigma, std::uint64_t seed) {
  Random rng(seed);
  NoisySet s{Eigen::MatrixXd(rows, 2), Eigen::MatrixXd(rows, 1), Eigen::MatrixXd(rows, 1)};
  for (int r = 0; r < rows; ++r) {
    s.x(r, 0) = rng.uniform(0.04, 0.10), s.x(r, 1) = rng.uniform(-20, 20);
    s.truth(r, 0) = study_rq(s.x(r, 0), s.x(r, 1));
    s.y(r, 0) = s.truth(r, 0) + sigma * rng.normal();
  }
  return s;
}

}  // namespace spreadmap::test
