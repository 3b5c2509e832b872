#include "powder/size_distribution.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>
#include <string>

#include <fmt/format.h>

namespace spreadmap::powder {
namespace {

constexpr int normal_panels = 4096;  // of the normal's table over ln d

double normal_cdf(double x) { return 0.5 * std::erfc(-x / std::sqrt(2.0)); }
double normal_pdf(double x) { return std::exp(-0.5 * x * x) / std::sqrt(2.0 * std::numbers::pi); }

// Exponent of d in the density per ln d of basis `by` when the distribution is stated in `given`:
// 3 (volume from number), -3 (number from volume) or 0.
double power_between(FractionBasis given, FractionBasis by) {
  return 3.0 * ((by == FractionBasis::volume) - (given == FractionBasis::volume));
}

// Mean of d^q over [a, b], uniform in ln d (a == b: one diameter).
double mean_power(double a, double b, double q) {
  if (a == b) return q == -3.0 ? 1.0 / (a * a * a) : std::pow(a, q);
  if (q == 0) return 1.0;
  return (std::pow(b, q) - std::pow(a, q)) / (q * std::log(b / a));
}

// Share of [a, b] below d (a < d < b) for a density per ln d proportional to d^q.
double class_share_below(double a, double b, double q, double d) {
  if (q == 0) return std::log(d / a) / std::log(b / a);
  return (std::pow(d, q) - std::pow(a, q)) / (std::pow(b, q) - std::pow(a, q));
}

// Each table row's share by `by`, normalised.
std::vector<double> class_shares(const SizeDistribution &s, FractionBasis by) {
  const double q = power_between(s.basis, by);
  std::vector<double> p(s.fractions.size());
  for (std::size_t i = 0; i < p.size(); ++i) p[i] = s.fractions[i] * mean_power(s.from[i], s.to[i], q);
  const double total = std::accumulate(p.begin(), p.end(), 0.0);
  for (double &v : p) v /= total;
  return p;
}

// The truncated normal as a table over ln d: number and volume accumulated panel by panel (midpoint
// rule, the density taken constant in ln d within a panel). sample() and cdf() both use it, so the
// quantiles cdf() gives are those of what sample() draws.
struct NormalTable {
  double ln_lo = 0, step = 0;
  std::vector<double> number, volume;  // accumulated up to each panel's upper edge, normalised

  explicit NormalTable(const SizeDistribution &s) {
    ln_lo = std::log(s.lower());
    step = (std::log(s.upper()) - ln_lo) / normal_panels;
    number.resize(normal_panels);
    volume.resize(normal_panels);
    const double q = power_between(s.basis, FractionBasis::number);
    double n = 0, v = 0;
    for (int k = 0; k < normal_panels; ++k) {
      const double d = std::exp(ln_lo + (k + 0.5) * step);
      const double per_ln_d = normal_pdf((d - s.d50) / s.standard_deviation) * d * std::pow(d, q);
      n += per_ln_d;
      v += per_ln_d * d * d * d;
      number[k] = n;
      volume[k] = v;
    }
    for (int k = 0; k < normal_panels; ++k) number[k] /= n, volume[k] /= v;
    mean_cube = v / n;
  }
  double mean_cube = 0;  // E[d^3] by number [m^3]

  double cdf(double d, FractionBasis by) const {
    const std::vector<double> &c = by == FractionBasis::volume ? volume : number;
    const double x = (std::log(d) - ln_lo) / step;
    if (x <= 0) return 0;
    if (x >= normal_panels) return 1;
    const int k = static_cast<int>(x);
    const double below = k > 0 ? c[k - 1] : 0.0;
    return below + (x - k) * (c[k] - below);
  }

  double draw(Random &random) const {
    const double u = random.uniform();
    const int k = static_cast<int>(std::upper_bound(number.begin(), number.end(), u) - number.begin());
    if (k >= normal_panels) return std::exp(ln_lo + normal_panels * step);
    const double below = k > 0 ? number[k - 1] : 0.0;
    return std::exp(ln_lo + (k + (u - below) / (number[k] - below)) * step);
  }
};

void check_truncation(const SizeDistribution &s) {
  if (s.d_min < 0 || s.d_max < 0 || (s.d_min > 0 && s.d_max > 0 && !(s.d_min < s.d_max)))
    throw PowderError(
        fmt::format("size distribution: truncation [d_min, d_max] = [{}, {}] m is not a range", s.d_min, s.d_max));
  if (!(s.lower() > 0) || !(s.lower() < s.upper()))
    throw PowderError(fmt::format("size distribution: truncation [{}, {}] m is not a range of positive diameters",
                                 s.lower(), s.upper()));
  if (!(s.lower() < s.d50 && s.d50 < s.upper()))
    throw PowderError(fmt::format("size distribution: truncation [{}, {}] m must contain the median d50 = {} m",
                                 s.lower(), s.upper(), s.d50));
}

// A lognormal or normal around d50, its width still to set.
SizeDistribution centred(SizeKind kind, double d50, FractionBasis basis, double d_min, double d_max) {
  SizeDistribution s;
  s.kind = kind;
  s.d50 = d50;
  s.basis = basis;
  s.d_min = d_min;
  s.d_max = d_max;
  return s;
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
  SizeDistribution s = centred(SizeKind::lognormal, d50, basis, d_min, d_max);
  s.sigma = sigma;
  return s;
}

SizeDistribution SizeDistribution::normal(double mean, double standard_deviation, FractionBasis basis, double d_min,
                                          double d_max) {
  SizeDistribution s = centred(SizeKind::normal, mean, basis, d_min, d_max);
  s.standard_deviation = standard_deviation;
  return s;
}

SizeDistribution SizeDistribution::table(std::vector<double> diameters, std::vector<double> fractions,
                                         FractionBasis basis) {
  std::vector<double> edges = diameters;
  return classes(std::move(diameters), std::move(edges), std::move(fractions), basis);
}

SizeDistribution SizeDistribution::classes(std::vector<double> from, std::vector<double> to,
                                           std::vector<double> fractions, FractionBasis basis) {
  SizeDistribution s;
  s.kind = SizeKind::table;
  s.from = std::move(from);
  s.to = std::move(to);
  s.fractions = std::move(fractions);
  s.basis = basis;
  return s;
}

void SizeDistribution::validate() const {
  auto positive = [](double v, const char *what) {
    if (!(v > 0) || !std::isfinite(v))
      throw PowderError(fmt::format("size distribution: {} = {} must be a positive finite length in m", what, v));
  };
  switch (kind) {
    case SizeKind::monodisperse:
      positive(diameter, "diameter");
      break;
    case SizeKind::lognormal:
      positive(d50, "d50");
      if (!(sigma >= 0) || !(sigma < 3))
        throw PowderError(
            fmt::format("size distribution: sigma = {} (standard deviation of ln d) must be in [0, 3)", sigma));
      if (sigma == 0) {
        if (!(lower() <= d50 && d50 <= upper()))
          throw PowderError(fmt::format("size distribution: truncation [{}, {}] m must contain d50 = {} m (sigma 0)",
                                       lower(), upper(), d50));
        break;
      }
      check_truncation(*this);
      // Samples are redrawn until inside: refuse a range that keeps almost nothing.
      if (normal_cdf(std::log(upper() / number_median()) / sigma) -
              normal_cdf(std::log(lower() / number_median()) / sigma) <
          1e-3)
        throw PowderError(fmt::format(
            "size distribution: truncation [{}, {}] m keeps less than 0.1 % of the particles of the lognormal", lower(),
            upper()));
      break;
    case SizeKind::normal:
      positive(d50, "the mean d50");
      positive(standard_deviation, "standard_deviation");
      if (d_min == 0 && !(d50 - 3 * standard_deviation > 0))
        throw PowderError(fmt::format(
            "size distribution: the normal's default lower bound d50 - 3 standard deviations = {} m is not positive; "
            "give d_min > 0",
            d50 - 3 * standard_deviation));
      check_truncation(*this);
      break;
    case SizeKind::table:
      if (from.empty() || from.size() != to.size() || from.size() != fractions.size())
        throw PowderError(fmt::format("size distribution: the table needs as many fractions as sizes (got {} and {})",
                                     from.size(), fractions.size()));
      for (std::size_t i = 0; i < from.size(); ++i) {
        positive(from[i], "a table diameter");
        positive(to[i], "a table diameter");
        if (!(from[i] <= to[i]))
          throw PowderError(fmt::format("size distribution: size class [{}, {}] m is reversed", from[i], to[i]));
      }
      for (double f : fractions)
        if (!(f >= 0) || !std::isfinite(f))
          throw PowderError(fmt::format("size distribution: fraction {} must be >= 0", f));
      if (!(std::accumulate(fractions.begin(), fractions.end(), 0.0) > 0))
        throw PowderError("size distribution: the table's fractions sum to 0");
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
      return d_min > 0 ? d_min : d50 * std::exp(-3.0 * sigma);
    case SizeKind::normal:
      return d_min > 0 ? d_min : d50 - 3.0 * standard_deviation;
    case SizeKind::table:
      return *std::min_element(from.begin(), from.end());
  }
  return diameter;
}

double SizeDistribution::upper() const {
  switch (kind) {
    case SizeKind::monodisperse:
      return diameter;
    case SizeKind::lognormal:
      return d_max > 0 ? d_max : d50 * std::exp(3.0 * sigma);
    case SizeKind::normal:
      return d_max > 0 ? d_max : d50 + 3.0 * standard_deviation;
    case SizeKind::table:
      return *std::max_element(to.begin(), to.end());
  }
  return diameter;
}

double SizeDistribution::mean_sphere_volume() const {
  switch (kind) {
    case SizeKind::monodisperse:
      return sphere_volume(diameter);
    case SizeKind::lognormal: {
      const double m = number_median();
      if (sigma == 0) return sphere_volume(m);
      // E[d^3] of a truncated lognormal: m^3 e^{9 s^2/2} [Phi(b - 3s) - Phi(a - 3s)] / [Phi(b) - Phi(a)].
      const double a = std::log(lower() / m) / sigma, b = std::log(upper() / m) / sigma;
      const double moment = m * m * m * std::exp(4.5 * sigma * sigma) *
                            (normal_cdf(b - 3 * sigma) - normal_cdf(a - 3 * sigma)) / (normal_cdf(b) - normal_cdf(a));
      return sphere_volume_factor * moment;
    }
    case SizeKind::normal:
      return sphere_volume_factor * NormalTable(*this).mean_cube;
    case SizeKind::table: {
      const std::vector<double> p = class_shares(*this, FractionBasis::number);
      const double q = power_between(basis, FractionBasis::number);
      double moment = 0;
      for (std::size_t i = 0; i < p.size(); ++i)
        moment += p[i] * mean_power(from[i], to[i], q + 3) / mean_power(from[i], to[i], q);
      return sphere_volume_factor * moment;
    }
  }
  return 0;
}

double SizeDistribution::cdf(double d, FractionBasis by) const {
  switch (kind) {
    case SizeKind::monodisperse:
      return d >= diameter ? 1.0 : 0.0;
    case SizeKind::lognormal: {
      if (sigma == 0) return d >= d50 ? 1.0 : 0.0;
      const double median = number_median() * (by == FractionBasis::volume ? std::exp(3.0 * sigma * sigma) : 1.0);
      auto phi = [&](double x) { return normal_cdf(std::log(x / median) / sigma); };
      const double lo = lower(), hi = upper();
      return (phi(std::clamp(d, lo, hi)) - phi(lo)) / (phi(hi) - phi(lo));
    }
    case SizeKind::normal:
      return NormalTable(*this).cdf(d, by);
    case SizeKind::table: {
      const std::vector<double> p = class_shares(*this, by);
      const double q = power_between(basis, by);
      double below = 0;
      for (std::size_t i = 0; i < p.size(); ++i) {
        if (d >= to[i]) below += p[i];
        else if (d > from[i]) below += p[i] * class_share_below(from[i], to[i], q, d);
      }
      return std::min(below, 1.0);
    }
  }
  return 0;
}

double SizeDistribution::quantile(double p, FractionBasis by) const {
  // Bisection in ln d for the smallest d with cdf(d) >= p (a table's steps included).
  double lo = lower(), hi = upper();
  if (cdf(lo, by) >= p) return lo;
  for (int i = 0; i < 200 && hi / lo - 1 > 1e-13; ++i) {
    const double mid = std::sqrt(lo * hi);
    (cdf(mid, by) >= p ? hi : lo) = mid;
  }
  return hi;
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
    case SizeKind::normal: {
      const NormalTable table(*this);
      while (d.size() < n) d.push_back(table.draw(random));
      break;
    }
    case SizeKind::table: {
      // Largest-remainder apportionment: counts as close to n p_i as whole numbers allow.
      const std::vector<double> p = class_shares(*this, FractionBasis::number);
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
      // Within a class, by number: d^q per ln d, drawn by inverting class_share_below.
      const double q = power_between(basis, FractionBasis::number);
      for (std::size_t i = 0; i < p.size(); ++i) {
        const double a = from[i], b = to[i];
        if (a == b) {
          d.insert(d.end(), count[i], a);
          continue;
        }
        for (std::size_t k = 0; k < count[i]; ++k) {
          const double u = random.uniform();
          d.push_back(q == 0 ? a * std::pow(b / a, u)
                             : std::pow(std::pow(a, q) + u * (std::pow(b, q) - std::pow(a, q)), 1.0 / q));
        }
      }
      break;
    }
  }
  return d;
}

}  // namespace spreadmap::powder
