#include "powder/size_fit.hpp"

#include <algorithm>
#include <cmath>

namespace spreadmap::powder {
namespace {

constexpr double z[3] = {-z_90, 0.0, z_90};

double worst_miss(const double given[3], const double fitted[3]) {
  double worst = 0;
  for (int i = 0; i < 3; ++i) worst = std::max(worst, std::abs(fitted[i] / given[i] - 1));
  return worst;
}

}  // namespace

QuantileFit fit_lognormal(double d10, double d50, double d90) {
  const double given[3] = {d10, d50, d90};
  QuantileFit fit;
  fit.d50 = std::exp((std::log(d10) + std::log(d50) + std::log(d90)) / 3);
  fit.spread = std::log(d90 / d10) / (2 * z_90);
  double fitted[3];
  for (int i = 0; i < 3; ++i) fitted[i] = fit.d50 * std::exp(fit.spread * z[i]);
  fit.misfit = worst_miss(given, fitted);
  return fit;
}

QuantileFit fit_normal(double d10, double d50, double d90) {
  const double given[3] = {d10, d50, d90};
  QuantileFit fit;
  fit.d50 = (d10 + d50 + d90) / 3;
  fit.spread = (d90 - d10) / (2 * z_90);
  double fitted[3];
  for (int i = 0; i < 3; ++i) fitted[i] = fit.d50 + fit.spread * z[i];
  fit.misfit = worst_miss(given, fitted);
  return fit;
}

}  // namespace spreadmap::powder
