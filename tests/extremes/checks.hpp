// The physical truths the stability suite asserts about a scene's state: every number finite, no
// sphere sunk into the substrate or the roller beyond the overlap limit, and the mechanical energy
// (to tell "the energy did not grow without a driver").
#pragma once
#include <engine/particle_set.hpp>

#include <string>

#include "extremes/scene.hpp"

namespace spreadmap::extremes {

// "" when every position, velocity, angular velocity, radius and mass is finite; else the first
// offending particle, for the assertion message.
std::string first_non_finite(const engine::ParticleSet &s);

// Deepest overlap with the substrate z = 0, as a fraction of the sphere's diameter (<= 0: none).
double deepest_substrate_overlap(const engine::ParticleSet &s);

// Deepest overlap with the roller at time t, as a fraction of the sphere's diameter (<= 0: none);
// `centre_inside` counts centres inside the solid cylinder (a sphere that tunnelled in).
struct RollerOverlap {
  double deepest = 0;
  std::size_t centre_inside = 0;
};
RollerOverlap roller_overlap(const spreader::Roller &roller, const engine::ParticleSet &s, double t);

// Mechanical energy above "every sphere resting on the substrate" [J]: translational and rotational
// kinetic energy, gravity measured from z = r, and the elastic energy of every linear normal spring
// (pairs, substrate, end walls and roller; K = m_eq omega0^2 for hooke_slider). Zero for spheres at
// rest on the floor; a scene without a driver can only lose it (dashpots, friction, removal).
struct Energy {
  double kinetic = 0, rotational = 0, gravity = 0, elastic = 0;
  double total() const { return kinetic + rotational + gravity + elastic; }
};
Energy mechanical_energy(const Scene &scene);

// Fastest sphere [m/s].
double top_speed(const engine::ParticleSet &s);

}  // namespace spreadmap::extremes
