// Device copies of the engine's structure-of-arrays views: particles, the CSR pair list with its
// history, and one wall's dense contact records. upload() copies host arrays in, view() hands the
// plugins' kernels the same view structs with device pointers, download*() copies results back.
// Buffers keep their memory while the sizes stay the same, so state can live on the GPU across steps.
#pragma once
#include <spreadmap/batch.hpp>

#include <array>
#include <cstdint>

#include "cuda/device_array.hpp"

namespace spreadmap::cuda {

template <class Real> class DeviceParticles {
 public:
  void upload(const Particles<Real> &host) {
    scalars_ = host;
    const Real *from[fields] = {host.x, host.y, host.z,  host.vx, host.vy, host.vz, host.wx, host.wy, host.wz,
                                host.r, host.m, host.fx, host.fy, host.fz, host.tx, host.ty, host.tz};
    for (int k = 0; k < fields; ++k) a_[k].upload(from[k], host.n);
  }
  // The kinematic arrays only (x, v, w), as between two force evaluations.
  void upload_motion(const Particles<Real> &host) {
    const Real *from[9] = {host.x, host.y, host.z, host.vx, host.vy, host.vz, host.wx, host.wy, host.wz};
    for (int k = 0; k < 9; ++k) a_[k].upload(from[k], host.n);
  }
  void set_time(Real t) { scalars_.t = t; }
  Particles<Real> view() const {
    Particles<Real> p = scalars_;
    p.x = a_[0].data();
    p.y = a_[1].data();
    p.z = a_[2].data();
    p.vx = a_[3].data();
    p.vy = a_[4].data();
    p.vz = a_[5].data();
    p.wx = a_[6].data();
    p.wy = a_[7].data();
    p.wz = a_[8].data();
    p.r = a_[9].data();
    p.m = a_[10].data();
    p.fx = a_[11].data();
    p.fy = a_[12].data();
    p.fz = a_[13].data();
    p.tx = a_[14].data();
    p.ty = a_[15].data();
    p.tz = a_[16].data();
    return p;
  }
  // Copies the force and torque accumulators into host's arrays.
  void download_accumulators(const Particles<Real> &host) const {
    Real *to[6] = {host.fx, host.fy, host.fz, host.tx, host.ty, host.tz};
    for (int k = 0; k < 6; ++k) a_[11 + k].download(to[k]);
  }

 private:
  static constexpr int fields = 17;
  Particles<Real> scalars_{};
  std::array<DeviceArray<Real>, fields> a_;
};

template <class Real> class DevicePairList {
 public:
  void upload(const PairList<Real> &host, std::uint32_t n, unsigned history) {
    const std::uint32_t entries = host.start[n];
    start_.upload(host.start, std::size_t(n) + 1);
    nbr_.upload(host.nbr, entries);
    hist_.upload(host.hist, std::size_t(entries) * history);
  }
  PairList<Real> view() const { return {start_.data(), nbr_.data(), hist_.data()}; }
  void download_history(const PairList<Real> &host) const { hist_.download(host.hist); }

 private:
  DeviceArray<std::uint32_t> start_, nbr_;
  DeviceArray<Real> hist_;
};

template <class Real> class DeviceWalls {
 public:
  void upload(const WallContacts<Real> &host, unsigned history) {
    n_ = host.n;
    const Real *from[7] = {host.overlap, host.nx, host.ny, host.nz, host.vx, host.vy, host.vz};
    for (int k = 0; k < 7; ++k) a_[k].upload(from[k], n_);
    hist_.upload(host.hist, std::size_t(n_) * history);
  }
  WallContacts<Real> view() const {
    return {n_,           a_[0].data(), a_[1].data(), a_[2].data(), a_[3].data(),
            a_[4].data(), a_[5].data(), a_[6].data(), hist_.data()};
  }
  // Copies the records (written by a geometry) and the history (written by a law) back.
  void download(const WallContacts<Real> &host) const {
    Real *to[7] = {host.overlap, host.nx, host.ny, host.nz, host.vx, host.vy, host.vz};
    for (int k = 0; k < 7; ++k) a_[k].download(to[k]);
    hist_.download(host.hist);
  }

 private:
  std::uint32_t n_ = 0;
  std::array<DeviceArray<Real>, 7> a_;
  DeviceArray<Real> hist_;
};

}  // namespace spreadmap::cuda
