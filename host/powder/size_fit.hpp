// A lognormal or normal from the three quantiles users quote, D10, D50 and D90 (in one basis).
//
// Two parameters, three quantiles: a least-squares fit. With z_p = Phi^-1(p) (z_10 = -z_90,
// z_50 = 0, z_90 = 1.2816) the quantiles of the family are
//   lognormal: ln D_p = ln d50 + sigma z_p,    normal: D_p = mean + standard_deviation z_p.
// Least squares over the three (in ln d for the lognormal, in d for the normal) gives
//   lognormal: ln d50 = (ln D10 + ln D50 + ln D90) / 3,  sigma = ln(D90 / D10) / (2 z_90)
//   normal:    mean = (D10 + D50 + D90) / 3,             standard_deviation = (D90 - D10) / (2 z_90)
// so D10 and D90 set the width and all three the centre. When D50^2 = D10 D90 (lognormal) or
// D50 = (D10 + D90) / 2 (normal) the fit reproduces all three exactly; otherwise `misfit` says by
// how much it misses the worst of them.
#pragma once

namespace spreadmap::powder {

inline constexpr double z_90 = 1.2815515655446004;  // Phi^-1(0.9)
// Largest relative miss of D10/D50/D90 that still counts as "of this family" (spreadmap warns above).
inline constexpr double quantile_misfit_tolerance = 0.05;

struct QuantileFit {
  double d50 = 0;     // lognormal median, normal mean [m]
  double spread = 0;  // lognormal sigma of ln d [-], normal standard deviation [m]
  double misfit = 0;  // max over D10, D50, D90 of |fitted / given - 1|
};

// Require 0 < d10 < d50 < d90.
QuantileFit fit_lognormal(double d10, double d50, double d90);
QuantileFit fit_normal(double d10, double d50, double d90);

}  // namespace spreadmap::powder
