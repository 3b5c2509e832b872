// The GPU kernels of a loaded contact or spreader plugin, and launching them over device views.
// A plugin built without CUDA has no CUDA entry point: asking for its kernels is a PluginError that
// says so and how to fix it.
#pragma once
#include <spreadmap/batch.hpp>
#include <spreadmap/cuda/abi.hpp>

#include <string>

#include "core/registry.hpp"

namespace spreadmap::cuda {

struct ContactKernels {
  std::string id;  // "contact/<name>", for messages
  const sm_contact_cuda_ops_v1 *ops = nullptr;
};
struct GeometryKernels {
  std::string id;  // "spreader/<name>"
  const sm_geometry_cuda_ops_v1 *ops = nullptr;
};

ContactKernels contact_kernels(const LoadedPlugin &plugin);
GeometryKernels spreader_kernels(const LoadedPlugin &plugin);

// Enqueue one kernel on `device`, on `stream` (a cudaStream_t; null: the device's default stream).
// Views hold device pointers; `law`/`geometry` is the bound instance in host memory. They do not
// wait; synchronize() (device_array.hpp) does, and reports kernel faults.
template <class Real>
void launch_pairs(const ContactKernels &k, const void *law, const Particles<Real> &p, const PairList<Real> &list,
                  int device = 0, void *stream = nullptr);
template <class Real>
void launch_walls(const ContactKernels &k, const void *law, const Particles<Real> &p, const WallContacts<Real> &w,
                  int device = 0, void *stream = nullptr);
template <class Real>
void launch_geometry(const GeometryKernels &k, const void *geometry, const Particles<Real> &p,
                     const WallContacts<Real> &w, int device = 0, void *stream = nullptr);

}  // namespace spreadmap::cuda
