// The gpu tests' spreading case: the quickstart's scene (roller, substrate, periodic strip) with a
// low heap of 400 spheres that settles in a few thousand steps.
#pragma once
#include <filesystem>
#include <string>

#include "gpu/gpu_support.hpp"
#include "workflow/file/workflow.hpp"
#include "workflow/spreading/scene_section.hpp"
#include "workflow/stage_table.hpp"

inline spreadmap::Scene small_spreading_scene(const std::string &precision) {
  namespace sm = spreadmap;
  sm::Diagnostics diag;
  const auto resolved =
      sm::resolve_scene(sm::load_workflow(std::filesystem::path(SPREADMAP_SOURCE_DIR) / "workflows" / "quickstart.yaml",
                                          sm::stage_names()),
                        registry(), diag);
  diag.throw_if_any();
  sm::Scene scene = *resolved;
  scene.powder.count = 400;  // a low heap over the preset's 6-13 mm (a 3 mm heap would sit under the roller)
  scene.powder.settle_time = 0.02;
  scene.spreader.params["U"] = 0.1;
  scene.precision = precision == "float" ? sm::Precision::float32 : sm::Precision::float64;
  return scene;
}
