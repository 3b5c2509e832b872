// Particles from a CSV file: a header line naming the columns (any order, case-insensitive),
// then one particle per line. Required: x, y, z, radius [m]. Optional: vx, vy, vz [m/s],
// wx, wy, wz [rad/s], mass [kg] or density [kg/m^3] (not both: the mass is then computed), id,
// fixed (0 or 1: the particle never moves). Blank lines and lines starting with '#' are skipped.
// Errors name the file, line and column (1-based) and what was expected.
#pragma once
#include <engine/particle_set.hpp>

#include <filesystem>
#include <vector>

namespace spreadmap::engine {

// `lines`, when given, receives the line number of each particle (for messages about it).
ParticleSet read_particles_csv(const std::filesystem::path &path, std::vector<std::size_t> *lines = nullptr);

}  // namespace spreadmap::engine
