#include "core/schema.hpp"

#include <fmt/format.h>

#include <spreadmap/digest.hpp>

#include <cmath>
#include <filesystem>
#include <stdexcept>
#include <nlohmann/json.hpp>
#include <yaml-cpp/yaml.h>

#include "core/files.hpp"
#include "core/suggest.hpp"
#include "core/units.hpp"

namespace spreadmap {
namespace {

const char *type_name(sm_param_type t) {
  switch (t) {
    case SM_NUMBER:
      return "number";
    case SM_INTEGER:
      return "integer";
    case SM_BOOLEAN:
      return "boolean";
    case SM_ENUM:
      return "enum";
    case SM_STRING:
      return "string";
    case SM_TABLE:
      return "table";
  }
  return "?";
}

std::string fmt_num(double v) {
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  return fmt::format("{:g}", v);
}

std::string range_text(const sm_param_v1 &p) {
  return "[" + fmt_num(p.min) + ", " + fmt_num(p.max) + "]" +
         (p.unit && std::string(p.unit) != "-" ? std::string(" ") + p.unit : "");
}

// A path parameter (unit "path", spreadmap/params.hpp): resolved against the folder of the file that
// names it, refused when missing, passed on absolute with its content digest beside it.
void resolve_file_param(const std::string &key, nlohmann::json &out, const Location &at, const std::string &file,
                        const std::string &key_path, Diagnostics &diag) {
  namespace fs = std::filesystem;
  const fs::path name = out[key].get<std::string>();
  const fs::path resolved = name.is_absolute() || file.empty() ? name : fs::path(file).parent_path() / name;
  if (name.empty() || !fs::is_regular_file(resolved)) {
    diag.error(at, key_path, name.empty() ? std::string("no file named") : fmt::format("no file {}", resolved.string()),
               "a file's name is relative to the folder of the file that names it");
    out[key] = nullptr;
    return;
  }
  out[key] = fs::absolute(resolved).lexically_normal().string();
  out[key + "_digest"] = content_digest(read_text(resolved));
}

}  // namespace

const sm_param_v1 *SchemaView::find(const std::string &name) const {
  for (std::size_t i = 0; i < n; ++i)
    if (name == params[i].name) return &params[i];
  return nullptr;
}

nlohmann::json yaml_to_json(const YAML::Node &node) {
  if (!node.IsDefined() || node.IsNull()) return nullptr;
  if (node.IsSequence()) {
    auto a = nlohmann::json::array();
    for (const auto &n : node) a.push_back(yaml_to_json(n));
    return a;
  }
  if (node.IsMap()) {
    auto o = nlohmann::json::object();
    for (const auto &kv : node) o[kv.first.as<std::string>()] = yaml_to_json(kv.second);
    return o;
  }
  const std::string s = node.Scalar();
  try {
    std::size_t used = 0;
    const double v = std::stod(s, &used);
    if (used == s.size() && std::isfinite(v)) return v;
  } catch (...) {
  }
  if (s == "true") return true;
  if (s == "false") return false;
  return s;
}

YAML::Node json_to_yaml(const nlohmann::json &value) {
  YAML::Node node;  // null unless filled below
  if (value.is_object())
    for (const auto &[key, item] : value.items()) node[key] = json_to_yaml(item);
  else if (value.is_array())
    for (const auto &item : value) node.push_back(json_to_yaml(item));
  else if (value.is_boolean()) node = value.get<bool>() ? "true" : "false";
  else if (value.is_number_integer()) node = value.dump();
  else if (value.is_number())
    node = fmt::format("{}", value.get<double>());  // the shortest text that reads back exactly
  else if (value.is_string()) node = value.get<std::string>();
  return node;
}

std::size_t read_whole_number(const YAML::Node &value, const std::string &file, const std::string &key_path,
                              std::size_t lo, std::size_t hi, std::size_t fallback, Diagnostics &diag) {
  if (!value) return fallback;
  const std::string name = key_path.substr(key_path.rfind('.') + 1);
  const sm_param_v1 p = {name.c_str(),     SM_INTEGER, "-", double(lo), double(hi),
                         double(fallback), nullptr,    0,   nullptr,    ""};
  const auto before = diag.errors().size();
  const auto v = validate_value(p, value, file, key_path, diag);
  return diag.errors().size() != before || !v.is_number() ? fallback : v.get<std::size_t>();
}

nlohmann::json validate_value(const sm_param_v1 &p, const YAML::Node &value, const std::string &file,
                              const std::string &key_path, Diagnostics &diag) {
  const Location at = Location::of(file, value);
  if (p.type == SM_TABLE) return yaml_to_json(value);
  if (!value.IsScalar()) {
    diag.error(at, key_path,
               fmt::format("expected a {} here, found a {}", type_name(p.type),
                           value.IsSequence() ? "list"
                           : value.IsMap()    ? "mapping"
                                              : "null"),
               p.doc ? fmt::format("{}: {}", p.name, p.doc) : "");
    return nullptr;
  }
  const std::string s = value.Scalar();
  switch (p.type) {
    case SM_NUMBER: {
      double v;
      try {
        v = parse_in(s, p.unit ? p.unit : "-");
      } catch (const std::invalid_argument &e) {
        diag.error(at, key_path, e.what(), fmt::format("{} is {} in {}", p.name, p.doc ? p.doc : "a number", p.unit));
        return nullptr;
      }
      if (v < p.min || v > p.max) {
        diag.error(at, key_path, fmt::format("{} = {} is outside {}", p.name, s, range_text(p)),
                   fmt::format("{}: {}", p.name, p.doc ? p.doc : ""));
        return nullptr;
      }
      return v;
    }
    case SM_INTEGER: {
      try {
        std::size_t used = 0;
        const long v = std::stol(s, &used);
        if (used != s.size()) throw std::invalid_argument("x");
        if (v < p.min || v > p.max) {
          diag.error(at, key_path, fmt::format("{} = {} is outside {}", p.name, s, range_text(p)));
          return nullptr;
        }
        return v;
      } catch (...) {
        diag.error(at, key_path, fmt::format("'{}' is not a whole number", s), fmt::format("{}: {}", p.name, p.doc));
        return nullptr;
      }
    }
    case SM_BOOLEAN: {
      const std::string l = lower(s);
      if (l == "true" || l == "yes" || l == "on") return true;
      if (l == "false" || l == "no" || l == "off") return false;
      diag.error(at, key_path, fmt::format("'{}' is not a boolean: write true or false", s));
      return nullptr;
    }
    case SM_ENUM: {
      const auto choices = split(p.choices ? p.choices : "", '|');
      for (const auto &c : choices)
        if (iequals(c, s)) return c;
      const std::string near = closest(s, choices);
      diag.error(at, key_path, fmt::format("'{}' is not one of {}", s, join(choices, ", ")),
                 near.empty() ? "" : fmt::format("did you mean '{}'?", near));
      return nullptr;
    }
    case SM_STRING:
      return s;
    default:
      return nullptr;
  }
}

nlohmann::json validate_params(const SchemaView &schema, const YAML::Node &section, const std::string &file,
                               const std::string &key_path, Diagnostics &diag, const std::set<std::string> &skip,
                               bool fill) {
  auto out = nlohmann::json::object();
  const std::string prefix = key_path.empty() ? "" : key_path + ".";
  if (section.IsDefined() && !section.IsNull() && !section.IsMap()) {
    diag.error(Location::of(file, section), key_path, "expected a mapping of parameters (key: value)");
    return out;
  }
  std::vector<std::string> known;
  for (std::size_t i = 0; i < schema.n; ++i) known.push_back(schema.params[i].name);
  if (section.IsMap()) {
    for (const auto &kv : section) {
      const std::string key = kv.first.as<std::string>();
      if (skip.count(key)) continue;
      const sm_param_v1 *p = schema.find(key);
      if (!p) {
        std::vector<std::string> all = known;
        all.insert(all.end(), skip.begin(), skip.end());
        const std::string near = closest(key, all);
        diag.error(Location::of(file, kv.first), prefix + key, "unknown key",
                   (near.empty() ? std::string() : "did you mean '" + near + "'? ") + "known: " + join(all));
        continue;
      }
      out[key] = validate_value(*p, kv.second, file, prefix + key, diag);
      if (p->type == SM_STRING && p->unit && std::string(p->unit) == "path" && out[key].is_string())
        resolve_file_param(key, out, Location::of(file, kv.second), file, prefix + key, diag);
    }
  }
  if (fill) fill_defaults(schema, out, Location::of(file, section), key_path, diag);
  return out;
}

void fill_defaults(const SchemaView &schema, nlohmann::json &out, const Location &where, const std::string &key_path,
                   Diagnostics &diag) {
  const std::string prefix = key_path.empty() ? "" : key_path + ".";
  for (std::size_t i = 0; i < schema.n; ++i) {
    const sm_param_v1 &p = schema.params[i];
    if (out.contains(p.name)) continue;
    if (p.required) {
      diag.error(where, prefix + p.name, "required value missing",
                 fmt::format("add {}: <{}{}>  ({})", p.name, type_name(p.type),
                             p.unit && std::string(p.unit) != "-" ? std::string(" in ") + p.unit : "", p.doc));
      continue;
    }
    switch (p.type) {
      case SM_NUMBER:
        out[p.name] = p.def;
        break;
      case SM_INTEGER:
        out[p.name] = static_cast<long>(p.def);
        break;
      case SM_BOOLEAN:
        out[p.name] = p.def != 0;
        break;
      case SM_ENUM:
      case SM_STRING:
        out[p.name] = p.def_text ? p.def_text : "";
        break;
      case SM_TABLE:
        out[p.name] = nullptr;
        break;
    }
  }
}

nlohmann::json schema_json(const sm_plugin_v1 &d) {
  return {{"kind", d.kind},
          {"name", d.name},
          {"version", d.version},
          {"summary", d.summary ? d.summary : ""},
          {"params", params_json(SchemaView::of(d))}};
}

nlohmann::json params_json(const SchemaView &schema) {
  auto params = nlohmann::json::array();
  for (std::size_t i = 0; i < schema.n; ++i) {
    const auto &p = schema.params[i];
    nlohmann::json e = {{"name", p.name},
                        {"type", type_name(p.type)},
                        {"unit", p.unit ? p.unit : "-"},
                        {"doc", p.doc ? p.doc : ""},
                        {"required", p.required != 0}};
    if (p.type == SM_NUMBER || p.type == SM_INTEGER) {
      e["min"] = std::isinf(p.min) ? nlohmann::json(nullptr) : nlohmann::json(p.min);
      e["max"] = std::isinf(p.max) ? nlohmann::json(nullptr) : nlohmann::json(p.max);
    }
    if (!p.required) {
      if (p.type == SM_NUMBER) e["default"] = p.def;
      if (p.type == SM_INTEGER) e["default"] = static_cast<long>(p.def);
      if (p.type == SM_BOOLEAN) e["default"] = p.def != 0;
      if (p.type == SM_ENUM || p.type == SM_STRING) e["default"] = p.def_text ? p.def_text : "";
    }
    if (p.type == SM_ENUM) e["choices"] = split(p.choices ? p.choices : "", '|');
    params.push_back(e);
  }
  return params;
}

std::string describe_schema(const sm_plugin_v1 &d) {
  return fmt::format("{}/{} {} — {}\n", d.kind, d.name, d.version, d.summary ? d.summary : "") +
         describe_params(SchemaView::of(d));
}

std::string describe_params(const SchemaView &schema, const std::string &column) {
  std::string out = fmt::format("  {:<26} {:<8} {:<9} {:<22} {:<12} {}\n", column, "type", "unit", "range", "default",
                     "meaning");
  for (std::size_t i = 0; i < schema.n; ++i) {
    const auto &p = schema.params[i];
    std::string range, def;
    if (p.type == SM_NUMBER || p.type == SM_INTEGER) range = "[" + fmt_num(p.min) + ", " + fmt_num(p.max) + "]";
    if (p.type == SM_ENUM) range = p.choices ? p.choices : "";
    if (p.required) def = "required";
    else if (p.type == SM_NUMBER || p.type == SM_INTEGER) def = fmt_num(p.def);
    else if (p.type == SM_BOOLEAN) def = p.def != 0 ? "true" : "false";
    else if (p.def_text) def = p.def_text;
    out += fmt::format("  {:<26} {:<8} {:<9} {:<22} {:<12} {}\n", p.name, type_name(p.type), p.unit ? p.unit : "-",
                       range, def, p.doc ? p.doc : "");
  }
  return out;
}

nlohmann::json default_params(const sm_plugin_v1 &p, const std::string &what) {
  Diagnostics diag;
  auto values = validate_params(SchemaView::of(p), YAML::Node(), "<defaults>", what, diag);
  diag.throw_if_any();
  return values;
}

}  // namespace spreadmap
