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
// stream: a cudaStream_t; null copies on the device's default stream. Both return when the copy is
// done (to the device: when the host buffer may be reused and the stream's later work sees it).
void copy_to_device(void *device, const void *host, std::size_t bytes, void *stream = nullptr);
void copy_to_host(void *host, const void *device, std::size_t bytes, void *stream = nullptr);
// Waits for every kernel enqueued on `device` (by any module's runtime) and reports its errors.
void synchronize(int device, const std::string &doing);
void select_device(int device);
std::string device_name(int device);

template <class T> class DeviceArray {
 public:
  DeviceArray() = default;
  DeviceArray(const DeviceArray &) = delete;
  DeviceArray &operator=(const DeviceArray &) = delete;
  DeviceArray(DeviceArray &&o) noexcept
      : data_(std::exchange(o.data_, nullptr)),
        size_(std::exchange(o.size_, 0)),
        capacity_(std::exchange(o.capacity_, 0)) {}
  DeviceArray &operator=(DeviceArray &&o) noexcept {
    std::swap(data_, o.data_);
    std::swap(size_, o.size_);
    std::swap(capacity_, o.capacity_);
    return *this;
  }
  ~DeviceArray() { device_free(data_); }

  // Reallocates only to grow: cudaFree waits for the whole device, so a stepper that freed at each
  // list build would stall the other cases sharing the GPU (resident_stepper.hpp).
  void resize(std::size_t n) {
    if (n <= capacity_) {
      size_ = n;
      return;
    }
    device_free(data_);
    data_ = nullptr;
    size_ = capacity_ = 0;
    data_ = static_cast<T *>(device_alloc(n * sizeof(T)));
    size_ = capacity_ = n;
  }
  // stream: a cudaStream_t (null: the device's default stream), see copy_to_device.
  void upload(const T *host, std::size_t n, void *stream = nullptr) {
    resize(n);
    if (n) copy_to_device(data_, host, n * sizeof(T), stream);
  }
  void download(T *host, void *stream = nullptr) const {
    if (size_) copy_to_host(host, data_, size_ * sizeof(T), stream);
  }
  T *data() const { return data_; }
  std::size_t size() const { return size_; }

 private:
  T *data_ = nullptr;
  std::size_t size_ = 0, capacity_ = 0;
};

}  // namespace spreadmap::cuda
