#include "workflow/scene/spreader_span.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <exception>
#include <mutex>
#include <set>

#include "workflow/simulate/case_setup.hpp"

namespace spreadmap {

std::optional<SpanShortfall> spreader_span_shortfall(const sm_spreader_description_v2 &spreader,
                                                     const engine::Domain &domain) {
  if (!(spreader.length > 0)) return std::nullopt;  // unbounded along y
  const double lo = domain.lo[1], hi = domain.hi[1], width = hi - lo;
  const double from = spreader.y_centre - 0.5 * spreader.length, to = spreader.y_centre + 0.5 * spreader.length;
  const double slack = 1e-9 * width;  // a spreader written as exactly the width spans it
  if (from <= lo + slack && to >= hi - slack) return std::nullopt;
  SpanShortfall s;
  s.periodic = domain.periodic[1];
  s.what = fmt::format("the spreader spans y = {:g}..{:g} mm, the domain {:g}..{:g} mm{}", from * 1e3, to * 1e3,
                       lo * 1e3, hi * 1e3,
                       s.periodic ? ", periodic: the powder beyond its end is never spread, and a sphere that "
                                    "crosses the seam beside its end face appears inside it"
                                  : ": the powder beyond its ends is never spread");
  const double centre = 0.5 * (lo + hi);
  s.fix = spreader.length >= width - slack
              ? fmt::format("set spreader.y_centre: {:g} mm (the middle of the width)", centre * 1e3)
              : fmt::format("make spreader.length at least {:g} mm and set spreader.y_centre: {:g} mm", width * 1e3,
                            centre * 1e3);
  return s;
}

namespace {
// Whether this process has not said `text` yet: a run resolves its scene once per stage, and the
// same warning each time would read as many problems.
bool first_time(const std::string &text) {
  static std::mutex guard;
  static std::set<std::string> said;
  const std::lock_guard<std::mutex> lock(guard);
  return said.insert(text).second;
}
}  // namespace

void check_spreader_span(const Scene &scene, const YAML::Node &user, const std::string &file, PluginRegistry &registry,
                         Diagnostics &diag) {
  sm_spreader_description_v2 described{};
  try {
    described = describe_spreader(scene, registry, file);
  } catch (const std::exception &) {
    return;  // a spreader that cannot be bound is reported where it is bound
  }
  const auto shortfall = spreader_span_shortfall(described, make_domain(scene));
  if (!shortfall) return;
  if (!shortfall->periodic) {
    const std::string text = fmt::format("{}: scene.spreader: {}\n  {}", file, shortfall->what, shortfall->fix);
    if (first_time(text)) spdlog::warn("{}", text);
    return;
  }
  const YAML::Node section = user["spreader"];
  const YAML::Node at = section && section.IsMap() ? (section["y_centre"] ? section["y_centre"]
                                                      : section["length"] ? section["length"]
                                                                          : section)
                                                   : user;
  diag.error(Location::of(file, at), "scene.spreader.y_centre", shortfall->what, shortfall->fix);
}

}  // namespace spreadmap
