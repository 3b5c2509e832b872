// One-shot GPU evaluations over host arrays: copy the inputs to the device, run the plugin's kernel,
// copy the results back, exactly where the CPU tables (pairs_f64, walls_f64, contacts_f64) write them.
// They answer "does the GPU give the CPU's numbers" (tests/gpu) and serve as the reference use of the
// device state and launchers that a resident GPU engine strings together.
#pragma once
#include <spreadmap/batch.hpp>

#include "cuda/plugin_kernels.hpp"

namespace spreadmap::cuda {

// Adds the pair forces and torques to p's accumulators and updates list.hist, as pairs_f64 does.
template <class Real>
void compute_pair_forces(const ContactKernels &k, const void *law, const Particles<Real> &p, const PairList<Real> &list,
                         int device = 0);
// Adds one wall's forces to p's accumulators and updates w.hist, as walls_f64 does.
template <class Real>
void compute_wall_forces(const ContactKernels &k, const void *law, const Particles<Real> &p,
                         const WallContacts<Real> &w, int device = 0);
// Fills w's records for the geometry at time p.t, as contacts_f64 does (w.hist is left alone).
template <class Real>
void compute_geometry_contacts(const GeometryKernels &k, const void *geometry, const Particles<Real> &p,
                               const WallContacts<Real> &w, int device = 0);

}  // namespace spreadmap::cuda
