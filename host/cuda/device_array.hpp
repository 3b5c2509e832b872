// Device memory owned by the host side, with the few CUDA runtime calls the driver needs. The CUDA
// headers stay in device_array.cpp, so users of this header compile with the plain C++ compiler.
#pragma once
#include <cstddef>
#include <string>
#include <utility>

namespace spreadmap::cuda {

// Throw RunFailure "<doing> on the GPU: CUDA says '...'" for a CUDA error code (0: nothing).
void check(int cuda_error, const std::string &doing);
void *device_alloc(std::size_t bytes);
void device_free(void *pointer) noexcept;
void copy_to_device(void *device, const void *host, std::size_t bytes);
void copy_to_host(void *host, const void *device, std::size_t bytes);
// Waits for every kernel enqueued on `device` (by any module's runtime) and reports its errors.
void synchronize(int device, const std::string &doing);
void select_device(int device);
std::string device_name(int device);

template <class T> class DeviceArray {
 public:
  DeviceArray() = default;
  DeviceArray(const DeviceArray &) = delete;
  DeviceArray &operator=(const DeviceArray &) = delete;
  DeviceArray(DeviceArray &&o) noexcept : data_(std::exchange(o.data_, nullptr)), size_(std::exchange(o.size_, 0)) {}
  DeviceArray &operator=(DeviceArray &&o) noexcept {
    std::swap(data_, o.data_);
    std::swap(size_, o.size_);
    return *this;
  }
  ~DeviceArray() { device_free(data_); }

  // Keeps the memory when the size does not change (no reallocation per step).
  void resize(std::size_t n) {
    if (n == size_) return;
    device_free(data_);
    data_ = nullptr;
    size_ = 0;
    if (n) data_ = static_cast<T *>(device_alloc(n * sizeof(T)));
    size_ = n;
  }
  void upload(const T *host, std::size_t n) {
    resize(n);
    if (n) copy_to_device(data_, host, n * sizeof(T));
  }
  void download(T *host) const {
    if (size_) copy_to_host(host, data_, size_ * sizeof(T));
  }
  T *data() const { return data_; }
  std::size_t size() const { return size_; }

 private:
  T *data_ = nullptr;
  std::size_t size_ = 0;
};

}  // namespace spreadmap::cuda
