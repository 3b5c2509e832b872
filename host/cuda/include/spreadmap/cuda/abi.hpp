// The CUDA side of a contact or spreader plugin, version 1. A plugin built with CUDA exports, beside
// `spreadmap_plugin_v1`, one more C entry point returning a static table of kernel launchers:
//   contact plugins:  const sm_contact_cuda_ops_v1 *sm_contact_cuda_v1(void)
//   spreader plugins: const sm_geometry_cuda_ops_v1 *sm_spreader_cuda_v1(void)
// and sets SM_BACKEND_CUDA in its descriptor. The launchers run the same SM_HD functors as the CPU
// tables, one GPU thread per particle, over the same structure-of-arrays views holding device pointers.
//
// Each launcher enqueues one kernel and returns 0 without waiting for it, or returns nonzero with a
// sentence in err (no usable device, launch failure). `self` is the bound instance made by create()
// in host memory: it is copied by value into the kernel's parameters.
#pragma once
#include <spreadmap/abi.h>
#include <spreadmap/batch.hpp>

#define SPREADMAP_CUDA_ABI 1u
#define SPREADMAP_CONTACT_CUDA_ENTRY "sm_contact_cuda_v1"
#define SPREADMAP_SPREADER_CUDA_ENTRY "sm_spreader_cuda_v1"

extern "C" {

// Where a kernel runs. Every module carries its own static CUDA runtime, so the host names the device
// its arrays live on; stream is a cudaStream_t (null: the default stream of that device).
typedef struct sm_cuda_launch_v1 {
  int device;
  void *stream;
} sm_cuda_launch_v1;

typedef struct sm_contact_cuda_ops_v1 {
  uint32_t abi;      // SPREADMAP_CUDA_ABI
  uint32_t history;  // values per contact; equals the CPU table's
  int (*pairs_f64)(const void *self, const spreadmap::Particles<double> *p, const spreadmap::PairList<double> *list,
                   const sm_cuda_launch_v1 *at, sm_error *err);
  int (*pairs_f32)(const void *self, const spreadmap::Particles<float> *p, const spreadmap::PairList<float> *list,
                   const sm_cuda_launch_v1 *at, sm_error *err);
  int (*walls_f64)(const void *self, const spreadmap::Particles<double> *p, const spreadmap::WallContacts<double> *w,
                   const sm_cuda_launch_v1 *at, sm_error *err);
  int (*walls_f32)(const void *self, const spreadmap::Particles<float> *p, const spreadmap::WallContacts<float> *w,
                   const sm_cuda_launch_v1 *at, sm_error *err);
} sm_contact_cuda_ops_v1;

typedef struct sm_geometry_cuda_ops_v1 {
  uint32_t abi;  // SPREADMAP_CUDA_ABI
  int (*contacts_f64)(const void *self, const spreadmap::Particles<double> *p,
                      const spreadmap::WallContacts<double> *out, const sm_cuda_launch_v1 *at, sm_error *err);
  int (*contacts_f32)(const void *self, const spreadmap::Particles<float> *p, const spreadmap::WallContacts<float> *out,
                      const sm_cuda_launch_v1 *at, sm_error *err);
} sm_geometry_cuda_ops_v1;

typedef const sm_contact_cuda_ops_v1 *(*sm_contact_cuda_entry_v1)(void);
typedef const sm_geometry_cuda_ops_v1 *(*sm_spreader_cuda_entry_v1)(void);
}
