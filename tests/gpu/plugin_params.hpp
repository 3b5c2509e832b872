// Parameters for an instance made directly from a schema: every default (as the host fills them in),
// then `overrides` on top. A required parameter must be among the overrides.
#pragma once
#include <spreadmap/abi.h>
#include <spreadmap/params.hpp>

#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>

namespace spreadmap::test {

inline nlohmann::json schema_params(const sm_param_v1 *params, uint32_t n,
                                    const nlohmann::json &overrides = nlohmann::json::object()) {
  nlohmann::json j = nlohmann::json::object();
  for (uint32_t k = 0; k < n; ++k) {
    const sm_param_v1 &p = params[k];
    if (overrides.contains(p.name)) continue;
    if (p.required) throw std::invalid_argument(std::string("schema_params: '") + p.name + "' is required");
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
        j[p.name] = p.def_text;
        break;
      case SM_TABLE:
        break;
    }
  }
  for (const auto &[key, value] : overrides.items()) j[key] = value;
  return j;
}

// The JSON text a plugin's create() takes.
inline std::string plugin_params(const sm_plugin_v1 *d, const nlohmann::json &overrides = nlohmann::json::object()) {
  return schema_params(d->params, d->n_params, overrides).dump();
}

// A header-only law or geometry bound the way its plugin binds it.
template <class T> T bind_with(const nlohmann::json &overrides = nlohmann::json::object()) {
  return T::bind(Values(schema_params(T::params, sizeof(T::params) / sizeof(T::params[0]), overrides)));
}

}  // namespace spreadmap::test
