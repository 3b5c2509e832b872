// Test helper: a spreader's bound Values from its schema defaults plus overrides, as the host
// would pass them (every key present, SI).
#pragma once
#include <spreadmap/geometry.hpp>
#include <spreadmap/params.hpp>

#include <nlohmann/json.hpp>
#include <string>

namespace spreadmap::test {

template <std::size_t N> nlohmann::json schema_defaults(const sm_param_v1 (&params)[N]) {
  nlohmann::json j = nlohmann::json::object();
  for (const auto &p : params) {
    switch (p.type) {
      case SM_NUMBER:
        j[p.name] = p.def;
        break;
      case SM_INTEGER:
        j[p.name] = static_cast<long>(p.def);
        break;
      case SM_BOOLEAN:
        j[p.name] = p.def != 0;
        break;
      case SM_ENUM:
      case SM_STRING:
        j[p.name] = p.def_text ? p.def_text : "";
        break;
      case SM_TABLE:
        j[p.name] = nullptr;
        break;
    }
  }
  return j;
}

template <class Geometry> Geometry bind_with(const nlohmann::json &overrides = nlohmann::json::object()) {
  nlohmann::json j = schema_defaults(Geometry::params);
  for (auto it = overrides.begin(); it != overrides.end(); ++it) j[it.key()] = it.value();
  return Geometry::bind(Values(j));
}

// What a bound geometry says of itself, as the host reads it through the ABI.
template <class Geometry> sm_spreader_description_v2 description_of(const Geometry &g) {
  sm_spreader_description_v2 d{};
  g.describe(&d);
  return d;
}
template <class Geometry> sm_spreader_pose_v2 pose_of(const Geometry &g, double t) {
  sm_spreader_pose_v2 p{};
  g.pose(t, &p);
  return p;
}

}  // namespace spreadmap::test
