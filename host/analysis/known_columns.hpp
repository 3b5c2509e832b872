// The columns spreadmap writes and reads by name (the spreader's settings and the layer metrics), each
// with its SI unit and the symbol figures and reports print: the one table the report, the figures and
// train read a unit or a symbol from when a file does not say it. The metric contract (what the map,
// verify, the adaptive design and the report read, workflow/stage/plugin_needs.hpp) is the two metrics
// named below.
#pragma once
#include <string>
#include <vector>

namespace spreadmap {

struct KnownColumn {
  const char *name, *unit, *symbol;
};
const std::vector<KnownColumn> &known_columns();
const KnownColumn *known_column(const std::string &name);  // null: not one of spreadmap's
std::string known_unit(const std::string &name);           // "" for a column not in the table
std::string known_symbol(const std::string &name);         // the name itself for a column not in the table

// The metric contract: the volume spread rate V_s [m^2/s] and the layer's roughness R_q [m].
inline constexpr const char *spread_rate_column = "vs";
inline constexpr const char *roughness_column = "rq";
bool is_contract_metric(const std::string &name);

}  // namespace spreadmap
