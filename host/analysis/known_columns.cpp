#include "analysis/known_columns.hpp"

#include <algorithm>

namespace spreadmap {

const std::vector<KnownColumn> &known_columns() {
  static const std::vector<KnownColumn> columns = {
      {"U", "m/s", "U"},                                      // the spreader's traverse speed
      {"omega", "rad/s", "omega"},                            // the spreader's rotation rate
      {spread_rate_column, "m^2/s", "V_s"},                   // volume spread rate
      {roughness_column, "m", "R_q"},                         // roughness of the layer's surface
      {"mean_height", "m", "mean height"},                    // of the layer's surface
      {"solid_thickness", "m", "solid thickness"},            // solid volume per area
      {"packing_fraction", "", "packing"},                    // of the layer (unitless)
      {"largest_bare_patch", "m", "largest bare patch"},      // diameter of the largest uncovered area
  };
  return columns;
}

const KnownColumn *known_column(const std::string &name) {
  const auto &all = known_columns();
  const auto it = std::find_if(all.begin(), all.end(), [&](const KnownColumn &c) { return name == c.name; });
  return it == all.end() ? nullptr : &*it;
}

std::string known_unit(const std::string &name) {
  const KnownColumn *c = known_column(name);
  return c ? c->unit : "";
}

std::string known_symbol(const std::string &name) {
  const KnownColumn *c = known_column(name);
  return c ? c->symbol : name;
}

bool is_contract_metric(const std::string &name) { return name == spread_rate_column || name == roughness_column; }

}  // namespace spreadmap
