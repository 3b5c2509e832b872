// Validation of a YAML section against a plugin's parameter schema: unknown keys (closest key
// suggested), wrong type, wrong physical dimension, unknown unit, NaN or infinity, out of range,
// missing required values. The result is a JSON object with every schema key, numbers in SI.
#pragma once
#include <spreadmap/abi.h>

#include <nlohmann/json_fwd.hpp>
#include <set>
#include <string>

#include "core/diagnostics.hpp"

namespace spreadmap {

struct SchemaView {
  const sm_param_v1 *params = nullptr;
  std::size_t n = 0;
  const sm_param_v1 *find(const std::string &name) const;
  static SchemaView of(const sm_plugin_v1 &p) { return {p.params, p.n_params}; }
};

// Validates `section` (a YAML map, or undefined = all defaults). Keys in `skip` belong to the host
// and are ignored here. Problems go to `diag`; the returned object is complete only when none.
nlohmann::json validate_params(const SchemaView &schema, const YAML::Node &section, const std::string &file,
                               const std::string &key_path, Diagnostics &diag, const std::set<std::string> &skip = {},
                               bool fill_defaults = true);

// Every key of a plugin's schema at its default (SI); throws InputError when one is required. `what`
// names the plugin in that message ("surrogate/gp").
nlohmann::json default_params(const sm_plugin_v1 &p, const std::string &what);

// Adds the default of every schema key missing from `values`; records a missing required value.
void fill_defaults(const SchemaView &schema, nlohmann::json &values, const Location &where, const std::string &key_path,
                   Diagnostics &diag);

// Validates one value against one entry; returns its JSON form (SI) or records an error.
nlohmann::json validate_value(const sm_param_v1 &p, const YAML::Node &value, const std::string &file,
                              const std::string &key_path, Diagnostics &diag);

// A whole number in [lo, hi] at `value` (key `key_path` in `file`): `fallback` when the key is absent
// or its value is refused (the error recorded).
std::size_t read_whole_number(const YAML::Node &value, const std::string &file, const std::string &key_path,
                              std::size_t lo, std::size_t hi, std::size_t fallback, Diagnostics &diag);

// Plain JSON from YAML (tables): numbers become numbers, the rest strings, maps and lists as such.
nlohmann::json yaml_to_json(const YAML::Node &node);
// The other way, for parameters given in code (engine/plugin_law.hpp): numbers written so that they
// read back to the same double, strings as they are ("2.5 um" keeps its unit). The nodes carry no
// position, so messages name only the source and the key.
YAML::Node json_to_yaml(const nlohmann::json &value);

// The schema as a human table, for `spreadmap plugins NAME` (describe_schema, with the plugin's name
// and summary above) and `spreadmap stages NAME` (describe_params).
std::string describe_schema(const sm_plugin_v1 &p);
std::string describe_params(const SchemaView &schema, const std::string &column = "parameter");
// The schema as JSON, for `spreadmap plugins --format json` (schema_json: the plugin's name,
// version and summary beside params_json's list).
nlohmann::json schema_json(const sm_plugin_v1 &p);
nlohmann::json params_json(const SchemaView &schema);

}  // namespace spreadmap
