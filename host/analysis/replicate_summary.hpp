// Replicated runs of a design point (simulate: replicates) summarised for the later stages: per
// point the mean and the sample standard deviation (n - 1) of each metric over its replicates, and
// from those the noise of each mean that a surrogate may take as given (std^2 / replicates).
#pragma once
#include <Eigen/Dense>

#include <string>
#include <vector>

#include "table.hpp"

namespace spreadmap::analysis {

// The column of a metric's standard deviation over the replicates: "vs" -> "vs_std".
std::string std_column(const std::string &metric);
// The column holding how many replicates a row's means are over.
inline const char *replicates_column() { return "replicates"; }

// One row per point (in order of first appearance in `runs`): `case` (the point's id, from the
// column `point`), the `inputs` (of its first replicate), then for each metric its mean and its
// std_column (empty cells where no replicate, or for the std fewer than two, have a value), and the
// number of replicates. Undefined (empty) cells of a replicate are left out of its point's figures.
Table summarise_replicates(const Table &runs, const std::string &point, const std::vector<std::string> &inputs,
                           const std::vector<std::string> &metrics, const std::string &source);

// rows x outputs: std^2 / replicates of each output's mean, where the table has both columns and
// finite values; 0 elsewhere (no known noise: the model's own noise level alone).
Eigen::MatrixXd replicate_noise_variance(const Table &table, const std::vector<std::string> &outputs,
                                         const std::vector<std::size_t> &rows);

}  // namespace spreadmap::analysis
