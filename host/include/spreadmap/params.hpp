// Parameter schemas (declared by plugins) and bound values (validated, SI) as plugins see them.
// Host-side only: never used inside SM_HD code.
#pragma once
#include <spreadmap/abi.h>

#include <limits>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>

namespace spreadmap {

inline constexpr double unbounded = std::numeric_limits<double>::infinity();

// Thrown by a plugin's bind() for a constraint the schema cannot express; the registration macro
// turns it into sm_error text and the host adds the plugin's kind/name and the workflow position.
struct ParamError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Schema builders: `static constexpr sm_param_v1 params[] = {sm::number(...), ...};`
constexpr sm_param_v1 number(const char *name, const char *unit, double min, double max, double def, const char *doc) {
  return {name, SM_NUMBER, unit, min, max, def, nullptr, 0, nullptr, doc};
}
constexpr sm_param_v1 required_number(const char *name, const char *unit, double min, double max, const char *doc) {
  return {name, SM_NUMBER, unit, min, max, 0.0, nullptr, 1, nullptr, doc};
}
constexpr sm_param_v1 integer(const char *name, double min, double max, double def, const char *doc) {
  return {name, SM_INTEGER, "-", min, max, def, nullptr, 0, nullptr, doc};
}
constexpr sm_param_v1 boolean(const char *name, bool def, const char *doc) {
  return {name, SM_BOOLEAN, "-", 0, 1, def ? 1.0 : 0.0, nullptr, 0, nullptr, doc};
}
constexpr sm_param_v1 enumeration(const char *name, const char *choices, const char *def, const char *doc) {
  return {name, SM_ENUM, "-", 0, 0, 0, def, 0, choices, doc};
}
constexpr sm_param_v1 text(const char *name, const char *def, const char *doc) {
  return {name, SM_STRING, "-", 0, 0, 0, def, 0, nullptr, doc};
}
constexpr sm_param_v1 required_enumeration(const char *name, const char *choices, const char *doc) {
  return {name, SM_ENUM, "-", 0, 0, 0, nullptr, 1, choices, doc};
}
// A file the plugin reads (unit "path", required). The host resolves it against the folder of the file
// that names it, refuses one that is missing, and passes it absolute, with `<name>_digest`: the
// file's content_digest (spreadmap/digest.hpp) when the input was validated, so that a changed file
// makes a different case and the plugin can refuse a file changed since.
constexpr sm_param_v1 file_path(const char *name, const char *doc) {
  return {name, SM_STRING, "path", 0, 0, 0, nullptr, 1, nullptr, doc};
}
constexpr sm_param_v1 table(const char *name, const char *doc) {
  return {name, SM_TABLE, "-", 0, 0, 0, nullptr, 0, nullptr, doc};
}

// The validated parameters of one instance: every schema key is present (defaults filled in),
// numbers in SI. Reading a key the schema does not declare is a programming error (throws).
class Values {
 public:
  explicit Values(nlohmann::json j) : j_(std::move(j)) {}
  static Values parse(const char *json_text) { return Values(nlohmann::json::parse(json_text)); }
  double operator[](const std::string &key) const { return at(key).get<double>(); }
  long integer(const std::string &key) const { return at(key).get<long>(); }
  bool boolean(const std::string &key) const { return at(key).get<bool>(); }
  std::string str(const std::string &key) const { return at(key).get<std::string>(); }
  const nlohmann::json &json(const std::string &key) const { return at(key); }
  bool has(const std::string &key) const { return j_.contains(key) && !j_.at(key).is_null(); }
  const nlohmann::json &all() const { return j_; }

 private:
  const nlohmann::json &at(const std::string &key) const {
    if (!j_.contains(key)) throw ParamError("parameter '" + key + "' was not supplied by the host");
    return j_.at(key);
  }
  nlohmann::json j_;
};

}  // namespace spreadmap
