// Percentiles and shares of a sample of particle diameters, by number or by volume (= by mass for
// one density: each particle weighs d^3). Host-side only; header-only so plugins and tests share it.
//
// Convention (no interpolation): percentile(p) is the smallest diameter of the sample at which the
// cumulative share of the sorted diameters (count, or sum of d^3) reaches p, i.e. the inverse of the
// empirical distribution function. A percentile is always one of the sample's diameters. Example,
// diameters 1, 2, 3 by volume (weights 1, 8, 27, cumulative shares 1/36, 9/36, 1): D10 = 2, D50 =
// D90 = 3; by number (shares 1/3, 2/3, 1): D10 = 1, D50 = 2, D90 = 3.
#pragma once
#include <algorithm>
#include <cstddef>
#include <limits>
#include <utility>
#include <vector>

namespace spreadmap {

enum class SizeBasis { number, volume };

class SizeSample {
 public:
  explicit SizeSample(std::vector<double> diameters) : d_(std::move(diameters)) {
    std::sort(d_.begin(), d_.end());
    number_.reserve(d_.size());
    volume_.reserve(d_.size());
    double n = 0, v = 0;
    for (double d : d_) {
      number_.push_back(n += 1);
      volume_.push_back(v += d * d * d);
    }
  }

  std::size_t size() const { return d_.size(); }

  // The diameter below which (inclusive) a share p in (0, 1] lies; NaN for an empty sample or p
  // outside (0, 1].
  double percentile(double p, SizeBasis by) const {
    if (d_.empty() || !(p > 0 && p <= 1)) return std::numeric_limits<double>::quiet_NaN();
    const std::vector<double> &cum = cumulative(by);
    const double target = p * cum.back();
    const auto at = std::lower_bound(cum.begin(), cum.end(), target);
    return at == cum.end() ? d_.back() : d_[static_cast<std::size_t>(at - cum.begin())];
  }

  // Share of the sample (count or volume) with a diameter strictly below d; NaN when empty.
  double share_below(double d, SizeBasis by) const {
    if (d_.empty()) return std::numeric_limits<double>::quiet_NaN();
    const std::size_t below = static_cast<std::size_t>(std::lower_bound(d_.begin(), d_.end(), d) - d_.begin());
    const std::vector<double> &cum = cumulative(by);
    return below == 0 ? 0.0 : cum[below - 1] / cum.back();
  }

 private:
  const std::vector<double> &cumulative(SizeBasis by) const { return by == SizeBasis::volume ? volume_ : number_; }

  std::vector<double> d_;                // sorted ascending [m]
  std::vector<double> number_, volume_;  // cumulative count and cumulative d^3 of d_[0..i]
};

}  // namespace spreadmap
