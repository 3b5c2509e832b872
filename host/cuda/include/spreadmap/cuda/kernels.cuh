// GPU instantiation of the SDK's loops, compiled by nvcc into each contact and spreader plugin.
// A kernel runs one thread per particle over the very SM_HD bodies the OpenMP loops run
// (pair_forces_on, wall_force_on, geometry_contact_of): no physics is written twice, and each particle
// still sums its own contacts in list order, so results do not depend on the launch shape.
//
// Used through the generated companion source (host/cuda/companion.cu.in), which ends a plugin with
//   SPREADMAP_CONTACT_CUDA(Law)   or   SPREADMAP_SPREADER_CUDA(Geometry)
#pragma once
#include <cuda_runtime.h>
#include <spreadmap/contact.hpp>
#include <spreadmap/cuda/abi.hpp>
#include <spreadmap/geometry.hpp>

#include <cstdio>
#include <type_traits>

namespace spreadmap::cuda {

// 128 threads: enough warps to hide memory latency, few enough registers per block for the
// heavier laws (Hertz-Mindlin with history) to keep several blocks per multiprocessor.
inline constexpr unsigned threads_per_block = 128;

template <class Law, class Real>
__global__ void pair_kernel(const Law law, const Particles<Real> p, const PairList<Real> list) {
  const std::uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i < p.n) pair_forces_on(law, p, list, i);
}

template <class Law, class Real>
__global__ void wall_kernel(const Law law, const Particles<Real> p, const WallContacts<Real> w) {
  const std::uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i < w.n) wall_force_on(law, p, w, i);
}

template <class Geometry, class Real>
__global__ void geometry_kernel(const Geometry g, const Particles<Real> p, const WallContacts<Real> w) {
  const std::uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i < p.n) geometry_contact_of(g, p, w, i);
}

inline int fail(sm_error *err, const char *doing, cudaError_t e) {
  if (err) {
    err->code = static_cast<int>(e);
    std::snprintf(err->text, sizeof err->text, "%s: CUDA says '%s' (%s)", doing, cudaGetErrorString(e),
                  cudaGetErrorName(e));
  }
  return 1;
}

// Selects the host's device in this module's runtime, launches, and reports a launch error.
template <class Kernel, class... Args>
int launch(Kernel kernel, std::uint32_t n, const sm_cuda_launch_v1 *at, sm_error *err, Args... args) {
  const int device = at ? at->device : 0;
  if (const cudaError_t e = cudaSetDevice(device); e != cudaSuccess) return fail(err, "selecting the CUDA device", e);
  if (n == 0) return 0;
  const unsigned blocks = (n + threads_per_block - 1) / threads_per_block;
  kernel<<<blocks, threads_per_block, 0, at ? static_cast<cudaStream_t>(at->stream) : nullptr>>>(args...);
  if (const cudaError_t e = cudaGetLastError(); e != cudaSuccess) return fail(err, "launching the kernel", e);
  return 0;
}

template <class Law> struct ContactCudaOps {
  static const Law &law(const void *s) { return *static_cast<const Law *>(s); }
  template <class Real>
  static int pairs(const void *s, const Particles<Real> *p, const PairList<Real> *l, const sm_cuda_launch_v1 *at,
                   sm_error *err) {
    return in_loop_form<LoopForms::kernels>(law(s), [&](const auto &form) {
      return launch(pair_kernel<std::decay_t<decltype(form)>, Real>, p->n, at, err, form, *p, *l);
    });
  }
  template <class Real>
  static int walls(const void *s, const Particles<Real> *p, const WallContacts<Real> *w, const sm_cuda_launch_v1 *at,
                   sm_error *err) {
    return in_loop_form<LoopForms::kernels>(law(s), [&](const auto &form) {
      return launch(wall_kernel<std::decay_t<decltype(form)>, Real>, w->n, at, err, form, *p, *w);
    });
  }
  static constexpr sm_contact_cuda_ops_v1 table = {SPREADMAP_CUDA_ABI, Law::history,   &pairs<double>,
                                                   &pairs<float>,      &walls<double>, &walls<float>};
};

template <class Geometry> struct GeometryCudaOps {
  template <class Real>
  static int contacts(const void *s, const Particles<Real> *p, const WallContacts<Real> *w, const sm_cuda_launch_v1 *at,
                      sm_error *err) {
    return launch(geometry_kernel<Geometry, Real>, p->n, at, err, *static_cast<const Geometry *>(s), *p, *w);
  }
  static constexpr sm_geometry_cuda_ops_v1 table = {SPREADMAP_CUDA_ABI, &contacts<double>, &contacts<float>};
};

}  // namespace spreadmap::cuda

#define SPREADMAP_CONTACT_CUDA(LAW)                                             \
  extern "C" SM_EXPORT const sm_contact_cuda_ops_v1 *sm_contact_cuda_v1(void) { \
    return &::spreadmap::cuda::ContactCudaOps<LAW>::table;                      \
  }
#define SPREADMAP_SPREADER_CUDA(GEOMETRY)                                         \
  extern "C" SM_EXPORT const sm_geometry_cuda_ops_v1 *sm_spreader_cuda_v1(void) { \
    return &::spreadmap::cuda::GeometryCudaOps<GEOMETRY>::table;                  \
  }
