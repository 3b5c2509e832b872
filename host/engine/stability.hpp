// Critical time step of the velocity-Verlet scheme for a linear spring-dashpot contact whose
// dashpot sees the half-step velocity (LAMMPS/LIGGGHTS order: half kick, drift, force, half kick).
//
// With u_n the half-step velocity and a = omega dt, one step of the contact oscillator is
//   x_{n+1} = x_n + dt u_n,   u_{n+1} = u_n (1 - 2 zeta a) - omega^2 dt x_{n+1},
// i.e. (x, dt u) -> M (x, dt u), M = [[1, 1], [-a^2, 1 - 2 zeta a - a^2]],
// trace T = 2 - 2 zeta a - a^2, det D = 1 - 2 zeta a. Jury conditions for lambda^2 - T lambda + D:
//   P(1) = a^2 > 0,  |D| < 1  <=>  zeta a < 1,  P(-1) = 4 - 4 zeta a - a^2 > 0.
// The last is the binding one: a < 2 (sqrt(1 + zeta^2) - zeta) (and then zeta a < 1 holds).
// So dt_crit = 2 (sqrt(1 + zeta^2) - zeta) / omega; zeta = 0 gives the undamped 2 / omega.
#pragma once
#include <engine/walls.hpp>

namespace spreadmap::engine {

// Largest stable omega * dt for damping ratio zeta >= 0.
double stable_omega_dt(double zeta);

// dt_crit of one contact type: the law evaluated at (m_eq, r_eff). +infinity for a law without
// stiffness (natural_frequency <= 0).
double contact_critical_dt(const ContactLaw &law, double m_eq, double r_eff);

}  // namespace spreadmap::engine
