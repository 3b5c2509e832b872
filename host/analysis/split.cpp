#include "split.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <stdexcept>

#include "table.hpp"

namespace sm = spreadmap;

namespace spreadmap::analysis {

namespace {
// A seeded permutation that is the same on every platform (mt19937_64 is fully specified; the
// standard distributions are not, so we draw indices ourselves).
std::vector<std::size_t> shuffled(std::size_t n, std::uint64_t seed) {
  std::vector<std::size_t> p(n);
  std::iota(p.begin(), p.end(), std::size_t(0));
  std::mt19937_64 engine(seed);
  for (std::size_t i = n; i > 1; --i) std::swap(p[i - 1], p[engine() % i]);
  return p;
}
}  // namespace

Split study_split(std::size_t rows, std::uint64_t seed) {
  if (rows < 4) throw std::invalid_argument("a train/test split needs at least 4 rows, got " + std::to_string(rows));
  const std::size_t n_test =
      std::min(rows - 2, std::max<std::size_t>(2, std::size_t(std::lround(double(rows) * 10.0 / 45.0))));
  const auto p = shuffled(rows, seed);
  Split s;
  s.test.assign(p.begin(), p.begin() + long(n_test));
  s.train.assign(p.begin() + long(n_test), p.end());
  std::sort(s.test.begin(), s.test.end());
  std::sort(s.train.begin(), s.train.end());
  return s;
}

std::vector<Split> k_fold(std::size_t rows, std::size_t k, std::uint64_t seed) {
  if (k < 2 || k > rows)
    throw std::invalid_argument("k-fold needs 2 <= k <= rows (" + std::to_string(rows) +
                                "), got k = " + std::to_string(k));
  const auto p = shuffled(rows, seed);
  std::vector<Split> folds(k);
  for (std::size_t i = 0; i < rows; ++i)
    for (std::size_t f = 0; f < k; ++f) (i % k == f ? folds[f].test : folds[f].train).push_back(p[i]);
  for (auto &f : folds) std::sort(f.test.begin(), f.test.end()), std::sort(f.train.begin(), f.train.end());
  return folds;
}

Split split_from_column(const Table &table, const std::string &column) {
  const std::size_t c = table.column(column);
  Split s;
  for (std::size_t r = 0; r < table.rows(); ++r) {
    std::string v = table.text(r, c);
    std::transform(v.begin(), v.end(), v.begin(), [](unsigned char ch) { return char(std::tolower(ch)); });
    if (v == "train") s.train.push_back(r);
    else if (v == "test") s.test.push_back(r);
    else
      throw std::runtime_error(table.source() + ": row " + std::to_string(r + 1) + ", column '" + table.columns()[c] +
                               "': '" + table.text(r, c) + "' is neither train nor test");
  }
  if (s.train.size() < 2)
    throw std::runtime_error(table.source() + ": column '" + column + "' marks fewer than 2 rows as train");
  return s;
}

std::vector<std::string> split_labels(const Split &split, std::size_t rows) {
  std::vector<std::string> v(rows);
  for (auto r : split.train) v.at(r) = "train";
  for (auto r : split.test) v.at(r) = "test";
  return v;
}

}  // namespace spreadmap::analysis
