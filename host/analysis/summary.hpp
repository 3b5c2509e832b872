// Mean and sample standard deviation of repeated measurements (one value per random heap, say).
#pragma once
#include <cmath>
#include <vector>

namespace spreadmap::analysis {

struct MeanSd {
  double mean = 0, sd = 0;  // sd: NaN for fewer than two values
};

inline MeanSd mean_sd(const std::vector<double> &v) {
  MeanSd s;
  for (double x : v) s.mean += x / double(v.size());
  for (double x : v) s.sd += (x - s.mean) * (x - s.mean);
  s.sd = v.size() > 1 ? std::sqrt(s.sd / double(v.size() - 1)) : std::nan("");
  return s;
}

}  // namespace spreadmap::analysis
