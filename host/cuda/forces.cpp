#include "cuda/forces.hpp"

#include "cuda/device_state.hpp"

namespace spreadmap::cuda {

template <class Real>
void compute_pair_forces(const ContactKernels &k, const void *law, const Particles<Real> &p, const PairList<Real> &list,
                         int device) {
  select_device(device);
  DeviceParticles<Real> dp;
  DevicePairList<Real> dl;
  dp.upload(p);
  dl.upload(list, p.n, k.ops->history);
  launch_pairs(k, law, dp.view(), dl.view(), device);
  synchronize(device, k.id + " pair forces");
  dp.download_accumulators(p);
  dl.download_history(list);
}

template <class Real>
void compute_wall_forces(const ContactKernels &k, const void *law, const Particles<Real> &p,
                         const WallContacts<Real> &w, int device) {
  select_device(device);
  DeviceParticles<Real> dp;
  DeviceWalls<Real> dw;
  dp.upload(p);
  dw.upload(w, k.ops->history);
  launch_walls(k, law, dp.view(), dw.view(), device);
  synchronize(device, k.id + " wall forces");
  dp.download_accumulators(p);
  dw.download(w);
}

template <class Real>
void compute_geometry_contacts(const GeometryKernels &k, const void *geometry, const Particles<Real> &p,
                               const WallContacts<Real> &w, int device) {
  select_device(device);
  DeviceParticles<Real> dp;
  DeviceWalls<Real> dw;
  dp.upload(p);
  dw.upload(w, 0);
  launch_geometry(k, geometry, dp.view(), dw.view(), device);
  synchronize(device, k.id + " contacts");
  dw.download(w);  // the records; the history was not uploaded and is not touched
}

#define SPREADMAP_FORCES_FOR(Real)                                                                              \
  template void compute_pair_forces<Real>(const ContactKernels &, const void *, const Particles<Real> &,        \
                                          const PairList<Real> &, int);                                         \
  template void compute_wall_forces<Real>(const ContactKernels &, const void *, const Particles<Real> &,        \
                                          const WallContacts<Real> &, int);                                     \
  template void compute_geometry_contacts<Real>(const GeometryKernels &, const void *, const Particles<Real> &, \
                                                const WallContacts<Real> &, int);
SPREADMAP_FORCES_FOR(double)
SPREADMAP_FORCES_FOR(float)
#undef SPREADMAP_FORCES_FOR

}  // namespace spreadmap::cuda
