// Train/test splits of a table's rows: the study's 35/10, k-fold, or read from a column.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace spreadmap::analysis {

class Table;

struct Split {
  std::vector<std::size_t> train, test;  // row indices, ascending
};

// The study's split: 10 of 45 rows to test, chosen by a seeded shuffle. Other sizes keep the test
// share 10/45 (rounded), with at least 2 test rows and 2 training rows; needs >= 4 rows.
Split study_split(std::size_t rows, std::uint64_t seed = 1);
// k folds of a seeded shuffle; fold i tests the i-th part and trains on the rest. 2 <= k <= rows.
std::vector<Split> k_fold(std::size_t rows, std::size_t k, std::uint64_t seed = 1);
// Rows whose `column` reads `train` or `test` (case-insensitive); any other value is an error
// naming the file and line.
Split split_from_column(const Table &table, const std::string &column);
// The split as a column of `train` / `test` texts (rows in neither: empty).
std::vector<std::string> split_labels(const Split &split, std::size_t rows);

}  // namespace spreadmap::analysis
