// Whether a spreader spans the domain's width. A spreader geometry sees no periodic images, so across
// a periodic width one shorter than the width leaves powder that is never spread, and a sphere that
// crosses the seam beside its end face appears inside it (an overlap of a large part of its diameter:
// the run stops with a blow-up). With open sides the powder beyond its ends is only never spread.
#pragma once
#include <spreadmap/geometry.hpp>
#include <yaml-cpp/yaml.h>

#include <optional>
#include <string>

#include "core/diagnostics.hpp"
#include "core/registry.hpp"
#include "engine/domain.hpp"
#include "workflow/scene/scene_model.hpp"

namespace spreadmap {

struct SpanShortfall {
  bool periodic = false;  // across a periodic width: refused; open sides: a warning
  std::string what;       // the spreader's extent against the width's
  std::string fix;
};

// Empty when the spreader (its description's y_centre and length; length 0: unbounded) covers the
// domain's y extent.
std::optional<SpanShortfall> spreader_span_shortfall(const sm_spreader_description_v2 &spreader,
                                                     const engine::Domain &domain);

// validate's check of a workflow's scene: refuses a spreader short of a periodic width (file:line,
// scene.spreader.y_centre, the centred value as the fix) and warns of one short of an open width.
void check_spreader_span(const Scene &scene, const YAML::Node &user, const std::string &file, PluginRegistry &registry,
                         Diagnostics &diag);

}  // namespace spreadmap
