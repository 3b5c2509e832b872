// Particles from a CSV file: a header line naming the columns (any order, case-insensitive),
// then one particle per line. Required: x, y, z, radius [m]. Optional: vx, vy, vz [m/s],
// wx, wy, wz [rad/s], mass [kg], id. Blank lines and lines starting with '#' are skipped.
// Errors name the file, line and column (1-based) and what was expected.
#pragma once
#include <engine/particle_set.hpp>

#include <filesystem>

namespace spreadmap::engine {

ParticleSet read_particles_csv(const std::filesystem::path &path);

}  // namespace spreadmap::engine
