#include "workflow/figures/figure_style.hpp"
#include <yaml-cpp/yaml.h>

namespace spreadmap::figures {

namespace {
Style &style_in_use() {
  static Style s;
  return s;
}
}  // namespace

Style read_style(const YAML::Node &node, bool default_on, bool frames_allowed, const std::string &file,
                 const std::string &key, Diagnostics &diag) {
  Style s;
  s.on = default_on;
  if (!node) return s;
  const std::string hint = std::string("write render: true, render: false or render: {width: 1920, vector: pdf") +
                           (frames_allowed ? ", frames: true}" : "}");
  if (node.IsScalar()) {
    try {
      s.on = node.as<bool>();
    } catch (const YAML::Exception &) {
      diag.error(Location::of(file, node), key, "'" + node.Scalar() + "' is neither true nor false", hint);
    }
    return s;
  }
  if (!node.IsMap()) {
    diag.error(Location::of(file, node), key, "must be true, false or a map", hint);
    return s;
  }
  s.on = true;
  for (const auto &kv : node) {
    const std::string k = kv.first.as<std::string>();
    const std::string where = key + "." + k;
    try {
      if (k == "width") {
        s.width = kv.second.as<int>();
        if (s.width < 200 || s.width > 16384)
          diag.error(Location::of(file, kv.second), where, "must be from 200 to 16384 pixels", "e.g. width: 1920");
      } else if (k == "vector") {
        s.vector = kv.second.as<std::string>();
        if (s.vector != "pdf" && s.vector != "svg" && s.vector != "eps")
          diag.error(Location::of(file, kv.second), where, "'" + s.vector + "' is not pdf, svg or eps");
      } else if (k == "frames" && frames_allowed) {
        s.frames = kv.second.as<bool>();
      } else {
        diag.error(Location::of(file, kv.first), where, "unknown key",
                   frames_allowed ? "known: width, vector, frames" : "known: width, vector");
      }
    } catch (const YAML::Exception &) {
      diag.error(Location::of(file, kv.second), where,
                 "'" + (kv.second.IsScalar() ? kv.second.Scalar() : "?") + "' is not valid", hint);
    }
  }
  return s;
}

void use_style(const Style &style) { style_in_use() = style; }
const Style &current_style() { return style_in_use(); }

}  // namespace spreadmap::figures
