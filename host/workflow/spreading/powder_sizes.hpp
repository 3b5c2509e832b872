// The powder's size distribution from scene.powder's keys, and the checks across those keys that
// run before anything else.
//
//   distribution: mono        diameter
//   distribution: lognormal   d50 and sigma, or d10, d50 and d90 (least-squares fit, size_fit.hpp)
//   distribution: normal      d50 (the mean) and standard_deviation, or d10, d50 and d90
//   distribution: table       table: rows or a CSV file (size_table.hpp)
//   basis: number | volume | mass     what d10/d50/d90 and the table's fractions count
//   d_min, d_max                      truncation of the lognormal and the normal (0 = default)
#pragma once
#include "core/yaml_fwd.hpp"

#include <string>
#include <vector>

#include "core/diagnostics.hpp"
#include "powder/size_distribution.hpp"
#include "workflow/spreading/scene_model.hpp"

namespace spreadmap {

// Throws InputError when the keys cannot make a distribution (check_powder_sizes says why, first).
powder::SizeDistribution size_distribution(const Powder &powder);

// Checks the size keys of `powder` (validated, SI, its table resolved). `user` is the powder section
// as written in `file`, for positions and for which keys the user wrote. Problems go to `diag`;
// returns the warnings to show once: D10/D50/D90 that the family or the truncation does not reproduce
// within powder::quantile_misfit_tolerance.
std::vector<std::string> check_powder_sizes(const Powder &powder, const YAML::Node &user, const std::string &file,
                                            Diagnostics &diag);

}  // namespace spreadmap
