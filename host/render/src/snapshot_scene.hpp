// The 3-D pieces of a particle snapshot (shared by snapshot() and animation_frames()).
#pragma once

#include <spreadmap/render/figures.hpp>

#include <filesystem>
#include <vector>

#include <vtkActor.h>
#include <vtkSmartPointer.h>

namespace spreadmap::render::detail {

inline constexpr double mm = 1e3;  // metres -> millimetres: the scenes are drawn in mm

struct SnapshotScene {
  std::vector<vtkSmartPointer<vtkActor>> actors;
};

// speed_top: top of the colour range [m/s].
SnapshotScene build_snapshot_scene(const SnapshotInput& in, double speed_top);
double largest_speed(const SnapshotInput& in);
void render_snapshot(const SnapshotInput& in, const std::filesystem::path& png, const Options& opt, double speed_top);

// The spreader's body (its outline extruded along y, clipped to the domain's y extent; a stripe and
// a spoke showing its angle when it turns), in millimetres.
std::vector<vtkSmartPointer<vtkActor>> spreader_actors(const SpreaderShape& spreader, const DomainBox& domain);
// Height of the body's highest point, as placed and turned [m].
double spreader_top(const SpreaderShape& spreader);

}  // namespace spreadmap::render::detail
