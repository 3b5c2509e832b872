#include "scene/size_distribution.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>
#include <string>

#include <fmt/format.h>

namespace spreadmap::scene {
namespace {

constexpr double sphere_volume_factor = std::numbers::pi / 6.0;  // V = (pi/6) d^3

double normal_cdf(double x) { return 0.5 * std::erfc(-x / std::sqrt(2.0)); }

// Number fractions of a table, normalised.
std::vector<double> number_fractions(const SizeDistribution &s) {
  std::vector<double> p(s.fractions);
  if (s.basis == FractionBasis::volume)
    for (std::size_t i = 0; i < p.size(); ++i) p[i] /= s.diameters[i] * s.diameters[i] * s.diameters[i];
  const double total = std::accumulate(p.begin(), p.end(), 0.0);
  for (double &v : p) v /= total;
  return p;
}

}  // namespace

SizeDistribution SizeDistribution::monodisperse(double d) {
  SizeDistribution s;
  s.kind = SizeKind::monodisperse;
  s.diameter = d;
  return s;
}

SizeDistribution SizeDistribution::lognormal(double d50, double sigma, FractionBasis basis, double d_min,
                                             double d_max) {
  SizeDistribution s;
  s.kind = SizeKind::lognormal;
  s.d50 = d50;
  s.sigma = sigma;
  s.basis = basis;
  s.d_min = d_min;
  s.d_max = d_max;
  return s;
}

SizeDistribution SizeDistribution::table(std::vector<double> diameters, std::vector<double> fractions,
                                         FractionBasis basis) {
  SizeDistribution s;
  s.kind = SizeKind::table;
  s.diameters = std::move(diameters);
  s.fractions = std::move(fractions);
  s.basis = basis;
  return s;
}

void SizeDistribution::validate() const {
  auto positive = [](double v, const char *what) {
    if (!(v > 0) || !std::isfinite(v))
      throw SceneError(fmt::format("size distribution: {} = {} must be a positive finite length in m", what, v));
  };
  switch (kind) {
    case SizeKind::monodisperse:
      positive(diameter, "diameter");
      break;
    case SizeKind::lognormal:
      positive(d50, "d50");
      if (!(sigma >= 0) || !(sigma < 3))
        throw SceneError(
            fmt::format("size distribution: sigma = {} (standard deviation of ln d) must be in [0, 3)", sigma));
      if (d_min < 0 || d_max < 0 || (d_min > 0 && d_max > 0 && !(d_min < d_max)))
        throw SceneError(
            fmt::format("size distribution: truncation [d_min, d_max] = [{}, {}] m is not a range", d_min, d_max));
      if (sigma > 0 && (lower() >= number_median() || upper() <= number_median()))
        throw SceneError(fmt::format("size distribution: truncation [{}, {}] m must contain the number median {} m",
                                     lower(), upper(), number_median()));
      break;
    case SizeKind::table:
      if (diameters.empty() || diameters.size() != fractions.size())
        throw SceneError(
            fmt::format("size distribution: the table needs as many fractions as diameters (got {} and {})",
                        diameters.size(), fractions.size()));
      for (double d : diameters) positive(d, "a table diameter");
      for (double f : fractions)
        if (!(f >= 0) || !std::isfinite(f))
          throw SceneError(fmt::format("size distribution: fraction {} must be >= 0", f));
      if (!(std::accumulate(fractions.begin(), fractions.end(), 0.0) > 0))
        throw SceneError("size distribution: the table's fractions sum to 0");
      break;
  }
}

double SizeDistribution::number_median() const {
  return basis == FractionBasis::volume ? d50 * std::exp(-3.0 * sigma * sigma) : d50;
}

double SizeDistribution::lower() const {
  switch (kind) {
    case SizeKind::monodisperse:
      return diameter;
    case SizeKind::lognormal:
      return d_min > 0 ? d_min : number_median() * std::exp(-3.0 * sigma);
    case SizeKind::table:
      return *std::min_element(diameters.begin(), diameters.end());
  }
  return diameter;
}

double SizeDistribution::upper() const {
  switch (kind) {
    case SizeKind::monodisperse:
      return diameter;
    case SizeKind::lognormal:
      return d_max > 0 ? d_max : number_median() * std::exp(3.0 * sigma);
    case SizeKind::table:
      return *std::max_element(diameters.begin(), diameters.end());
  }
  return diameter;
}

double SizeDistribution::mean_sphere_volume() const {
  switch (kind) {
    case SizeKind::monodisperse:
      return sphere_volume_factor * diameter * diameter * diameter;
    case SizeKind::lognormal: {
      const double m = number_median();
      if (sigma == 0) return sphere_volume_factor * m * m * m;
      // E[d^3] of a truncated lognormal: m^3 e^{9 s^2/2} [Phi(b - 3s) - Phi(a - 3s)] / [Phi(b) - Phi(a)].
      const double a = std::log(lower() / m) / sigma, b = std::log(upper() / m) / sigma;
      const double moment = m * m * m * std::exp(4.5 * sigma * sigma) *
                            (normal_cdf(b - 3 * sigma) - normal_cdf(a - 3 * sigma)) / (normal_cdf(b) - normal_cdf(a));
      return sphere_volume_factor * moment;
    }
    case SizeKind::table: {
      const std::vector<double> p = number_fractions(*this);
      double moment = 0;
      for (std::size_t i = 0; i < p.size(); ++i) moment += p[i] * diameters[i] * diameters[i] * diameters[i];
      return sphere_volume_factor * moment;
    }
  }
  return 0;
}

std::vector<double> SizeDistribution::sample(std::size_t n, Random &random) const {
  validate();
  std::vector<double> d;
  d.reserve(n);
  switch (kind) {
    case SizeKind::monodisperse:
      d.assign(n, diameter);
      break;
    case SizeKind::lognormal: {
      const double m = number_median(), lo = lower(), hi = upper();
      while (d.size() < n) {
        const double v = m * std::exp(sigma * random.normal());
        if (v >= lo && v <= hi) d.push_back(v);
      }
      break;
    }
    case SizeKind::table: {
      // Largest-remainder apportionment: counts as close to n p_i as whole numbers allow.
      const std::vector<double> p = number_fractions(*this);
      std::vector<std::size_t> count(p.size());
      std::vector<std::pair<double, std::size_t>> remainder;
      std::size_t assigned = 0;
      for (std::size_t i = 0; i < p.size(); ++i) {
        const double exact = p[i] * static_cast<double>(n);
        count[i] = static_cast<std::size_t>(std::floor(exact));
        assigned += count[i];
        remainder.emplace_back(exact - static_cast<double>(count[i]), i);
      }
      std::stable_sort(remainder.begin(), remainder.end(),
                       [](const auto &a, const auto &b) { return a.first > b.first; });
      for (std::size_t k = 0; assigned < n; ++k, ++assigned) ++count[remainder[k % remainder.size()].second];
      for (std::size_t i = 0; i < p.size(); ++i) d.insert(d.end(), count[i], diameters[i]);
      break;
    }
  }
  return d;
}

}  // namespace spreadmap::scene
