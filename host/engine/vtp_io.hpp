// Particle snapshots as VTK XML PolyData (.vtp, ASCII, readable by ParaView and VTK) and series
// files (.pvd). Points are the centres; point data "velocity", "omega" (3 components), "radius",
// "mass", "id", and "fixed" (0/1, only when the set has the column: fixed particles never move);
// field data "TIME". Written atomically (write_atomic: a failed write throws
// RunFailure naming the file). read_vtp reads back files written by write_vtp (a small parser for
// this layout, not a general VTK reader).
#pragma once
#include <engine/particle_set.hpp>

#include <filesystem>
#include <string>
#include <vector>

namespace spreadmap::engine {

void write_vtp(const std::filesystem::path &path, const ParticleSet &state, double time);

struct VtpContent {
  ParticleSet particles;
  double time = 0;
};
// Throws SetupError naming the file and what is missing or malformed.
VtpContent read_vtp(const std::filesystem::path &path);

struct SeriesEntry {
  double time;       // [s]
  std::string file;  // relative to the .pvd file, e.g. "series/000012.vtp"
};
void write_pvd(const std::filesystem::path &path, const std::vector<SeriesEntry> &series);

}  // namespace spreadmap::engine
