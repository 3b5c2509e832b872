// Critical time step of the velocity-Verlet scheme for linear spring-dashpot contacts whose
// dashpot sees the half-step velocity (LAMMPS/LIGGGHTS order: half kick, drift, force, half kick).
//
// One contact. With u_n the half-step velocity and a = omega dt, one step of the contact oscillator is
//   x_{n+1} = x_n + dt u_n,   u_{n+1} = u_n (1 - 2 zeta a) - omega^2 dt x_{n+1},
// i.e. (x, dt u) -> M (x, dt u), M = [[1, 1], [-a^2, 1 - 2 zeta a - a^2]],
// trace T = 2 - 2 zeta a - a^2, det D = 1 - 2 zeta a. Jury conditions for lambda^2 - T lambda + D:
//   P(1) = a^2 > 0,  |D| < 1  <=>  zeta a < 1,  P(-1) = 4 - 4 zeta a - a^2 > 0.
// The last is the binding one: a < 2 (sqrt(1 + zeta^2) - zeta) (and then zeta a < 1 holds).
// So one contact is stable below 2 (sqrt(1 + zeta^2) - zeta) / omega; zeta = 0 gives 2 / omega.
//
// A packing. A sphere held by several contacts vibrates faster than any one of them. For equal
// spheres and central springs the fastest mode of the densest packing (face-centred cubic, 12
// contacts a sphere) is the zone-boundary mode at X, omega^2 = 8 K / m = 4 omega^2_contact
// (K = m omega^2_contact / 2 for m_eq = m / 2): twice the contact's frequency. Its dashpots scale
// as its springs, so its damping ratio is twice the contact's too. Close-packed slabs on a wall stay
// below it (1.73, 1.86, 1.93, 1.96 x for 1, 2, 3, 4 layers), and a random heap, with fewer
// contacts, lower still. The scene's dt_crit is therefore the limit of that mode:
//   dt_crit = stable_omega_dt(2 zeta) / (2 omega).
// Below it every packing the scene can form is stable; an isolated impact, which gains energy once
// a > sqrt(2) (it can then enter and leave within about two steps), is at a <= 1 there. The
// single-contact limit is 2 to 3.5 x larger (zeta from 0 to 1): a step between the two can run on a
// loose heap and blow up once the powder packs (measured: a settled heap of 150 spheres at 0.9 x
// the single-contact limit, epsilon = 0.8, gains 25 x its energy in 0.15 s).
#pragma once
#include <engine/walls.hpp>

namespace spreadmap::engine {

// Largest stable omega * dt for damping ratio zeta >= 0.
double stable_omega_dt(double zeta);

// How much faster than one contact the densest packing of equal spheres vibrates (see above).
inline constexpr double packing_frequency_factor = 2.0;

// Stability limit of one isolated contact of this type: the law evaluated at (m_eq, r_eff).
// +infinity for a law without stiffness (natural_frequency <= 0); 0 where no step is stable (the law's
// natural_frequency is +infinity: its attraction outweighs its stiffness, the contact collapses).
double contact_critical_dt(const ContactLaw &law, double m_eq, double r_eff);

// dt_crit of a scene whose contacts are of this type: the limit of the densest packing's fastest mode.
double packing_critical_dt(const ContactLaw &law, double m_eq, double r_eff);

}  // namespace spreadmap::engine
