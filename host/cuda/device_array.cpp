#include "cuda/device_array.hpp"

#include <cuda_runtime_api.h>

#include "core/error.hpp"

namespace spreadmap::cuda {

void check(int cuda_error, const std::string &doing) {
  if (cuda_error == cudaSuccess) return;
  const auto e = static_cast<cudaError_t>(cuda_error);
  throw RunFailure(doing + " on the GPU: CUDA says '" + cudaGetErrorString(e) + "' (" +
                   cudaGetErrorName(e) + ")");
}

void *device_alloc(std::size_t bytes) {
  void *p = nullptr;
  check(cudaMalloc(&p, bytes), "allocating " + std::to_string(bytes) + " bytes");
  return p;
}

void device_free(void *pointer) noexcept {
  if (pointer) cudaFree(pointer);
}

void copy_to_device(void *device, const void *host, std::size_t bytes, void *stream) {
  if (!stream) return check(cudaMemcpy(device, host, bytes, cudaMemcpyHostToDevice), "copying to the device");
  const auto s = static_cast<cudaStream_t>(stream);
  check(cudaMemcpyAsync(device, host, bytes, cudaMemcpyHostToDevice, s), "copying to the device");
  check(cudaStreamSynchronize(s), "copying to the device");
}

void copy_to_host(void *host, const void *device, std::size_t bytes, void *stream) {
  if (!stream) return check(cudaMemcpy(host, device, bytes, cudaMemcpyDeviceToHost), "copying from the device");
  const auto s = static_cast<cudaStream_t>(stream);
  check(cudaMemcpyAsync(host, device, bytes, cudaMemcpyDeviceToHost, s), "copying from the device");
  check(cudaStreamSynchronize(s), "copying from the device");
}

void synchronize(int device, const std::string &doing) {
  select_device(device);
  check(cudaDeviceSynchronize(), doing);
}

void select_device(int device) { check(cudaSetDevice(device), "selecting CUDA device " + std::to_string(device)); }

std::string device_name(int device) {
  cudaDeviceProp prop{};
  check(cudaGetDeviceProperties(&prop, device), "reading the properties of CUDA device " + std::to_string(device));
  return prop.name;
}

}  // namespace spreadmap::cuda
