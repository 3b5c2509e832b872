// The CUDA backend's step (resident_stepper.hpp): state resident in device memory, one kernel per
// stage, the engine's host-device functions inside. Compiled by nvcc into spreadmap_cuda.
#include "cuda/resident_stepper.hpp"

#include <cub/cub.cuh>
#include <cuda_runtime.h>

#include <chrono>
#include <cstring>
#include <map>
#include <string>

#include "core/error.hpp"
#include "cuda/device_array.hpp"
#include "engine/cell_grid.hpp"
#include "engine/errors.hpp"
#include "engine/kick_drift.hpp"
#include "engine/neighbour_listing.hpp"
#include "engine/walls.hpp"

namespace spreadmap::cuda {
namespace {

constexpr unsigned block_size = 128;  // a multiple of the warp: the reductions below need whole warps
unsigned blocks_for(std::size_t n) { return unsigned((n + block_size - 1) / block_size); }

void ok(cudaError_t e, const char *doing) { check(static_cast<int>(e), doing); }

// What a kernel pass reports to the host (copied back once per pass).
struct PassReport {
  unsigned long long d2_bits;  // largest squared displacement since the list build, a double's bits
  unsigned int escaped, nonfinite, bad;
};

__device__ unsigned long long warp_max(unsigned long long v) {
  for (int o = 16; o > 0; o >>= 1) {
    const unsigned long long w = __shfl_down_sync(0xffffffffu, v, o);
    v = w > v ? w : v;
  }
  return v;
}
__device__ unsigned long long warp_min(unsigned long long v) {
  for (int o = 16; o > 0; o >>= 1) {
    const unsigned long long w = __shfl_down_sync(0xffffffffu, v, o);
    v = w < v ? w : v;
  }
  return v;
}
__device__ unsigned int warp_sum(unsigned int v) {
  for (int o = 16; o > 0; o >>= 1) v += __shfl_down_sync(0xffffffffu, v, o);
  return v;
}

// Every lane of every warp calls this (lanes past the end with neutral values); lane 0 adds its
// warp's share. d2 >= 0 or NaN: its bits order as the values do, NaN above every number.
__device__ void add_report(PassReport *out, double d2, unsigned escaped, unsigned nonfinite, unsigned bad) {
  const unsigned long long m = warp_max(static_cast<unsigned long long>(__double_as_longlong(d2)));
  const unsigned e = warp_sum(escaped), f = warp_sum(nonfinite), b = warp_sum(bad);
  if ((threadIdx.x & 31u) != 0) return;
  if (m) atomicMax(&out->d2_bits, m);
  if (e) atomicAdd(&out->escaped, e);
  if (f) atomicAdd(&out->nonfinite, f);
  if (b) atomicAdd(&out->bad, b);
}

template <class Real, bool PX, bool PY, bool PZ, bool Rotate>
__global__ void kick_drift_kernel(engine::KickDrift<Real> k, std::uint32_t n, PassReport *out) {
  const std::uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
  double d2 = 0;
  unsigned escaped = 0, nonfinite = 0;
  if (i < n) {
    engine::detail::half_kick<Real, Rotate, false>(k, i);
    const engine::detail::Drifted<Real> d = engine::detail::drift<Real, PX, PY, PZ>(k, i);
    d2 = double(d.d2), escaped = d.escaped, nonfinite = d.nonfinite;
  }
  add_report(out, d2, escaped, nonfinite, 0);
}

template <class Real, bool Rotate>
__global__ void kick_check_kernel(engine::KickDrift<Real> k, Real limit2, std::uint32_t n, PassReport *out) {
  const std::uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
  unsigned bad = 0;
  if (i < n) {
    engine::detail::half_kick<Real, Rotate, false>(k, i);
    bad = engine::detail::too_fast(k, limit2, i);
  }
  add_report(out, 0.0, 0, 0, bad);
}

// Doubles as unsigned integers that order as the values do (for atomicMin / atomicMax).
__device__ unsigned long long ordered(double v) {
  const auto b = static_cast<unsigned long long>(__double_as_longlong(v));
  return (b >> 63) ? ~b : b | 0x8000000000000000ull;
}
double from_ordered(unsigned long long u) {
  const unsigned long long b = (u >> 63) ? u & 0x7fffffffffffffffull : ~u;
  double v;
  std::memcpy(&v, &b, sizeof v);
  return v;
}

struct Bounds {
  unsigned long long lo[3], hi[3], r_max;
};

template <class Real>
__global__ void bounds_kernel(const Real *x, const Real *y, const Real *z, const Real *r, std::uint32_t n,
                              Bounds *out) {
  const std::uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
  const Real *c[3] = {x, y, z};
  for (int a = 0; a < 3; ++a) {
    const unsigned long long lo = warp_min(i < n ? ordered(double(c[a][i])) : ~0ull);
    const unsigned long long hi = warp_max(i < n ? ordered(double(c[a][i])) : 0ull);
    if ((threadIdx.x & 31u) == 0) atomicMin(&out->lo[a], lo), atomicMax(&out->hi[a], hi);
  }
  const unsigned long long rm = warp_max(i < n ? ordered(double(r[i])) : 0ull);
  if ((threadIdx.x & 31u) == 0) atomicMax(&out->r_max, rm);
}

template <class Real>
__global__ void cell_kernel(engine::CellGrid<Real> grid, const Real *x, const Real *y, const Real *z, std::uint32_t n,
                            std::uint32_t *cell, std::uint32_t *index) {
  const std::uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i >= n) return;
  cell[i] = grid.cell_of(x[i], y[i], z[i]);
  index[i] = i;
}

__global__ void count_cells_kernel(const std::uint32_t *cell, std::uint32_t n, std::uint32_t *count) {
  const std::uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i < n) atomicAdd(&count[cell[i]], 1u);
}

template <class T>
__global__ void gather_kernel(const T *in, T *out, const std::uint32_t *from, std::uint32_t n, unsigned stride) {
  const std::uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i >= n) return;
  for (unsigned q = 0; q < stride; ++q) out[std::size_t(i) * stride + q] = in[std::size_t(from[i]) * stride + q];
}

// What the list kernels read: the sorted particles, the grid and its cell ranges.
template <class Real> struct ListArgs {
  const Real *x, *y, *z, *r;
  engine::CellGrid<Real> grid;
  const std::uint32_t *cell, *cell_start;
  Real len[3], skin;
  bool per[3];
  std::uint32_t n;
};

template <class Real> __global__ void list_count_kernel(ListArgs<Real> a, std::uint32_t *count) {
  const std::uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i >= a.n) return;
  const engine::CellRanges ranges = engine::neighbour_ranges(a.grid, a.cell[i], a.cell_start);
  count[i] = engine::list_neighbours(i, a.x, a.y, a.z, a.r, static_cast<const Real *>(nullptr), a.len, a.per, a.skin,
                                     ranges, static_cast<std::uint32_t *>(nullptr), 0u);
}

template <class Real>
__global__ void list_fill_kernel(ListArgs<Real> a, const std::uint32_t *start, std::uint32_t *nbr) {
  const std::uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i >= a.n) return;
  const engine::CellRanges ranges = engine::neighbour_ranges(a.grid, a.cell[i], a.cell_start);
  engine::list_neighbours(i, a.x, a.y, a.z, a.r, static_cast<const Real *>(nullptr), a.len, a.per, a.skin, ranges,
                          nbr + start[i], start[i + 1] - start[i]);
}

template <class Real>
__global__ void carry_kernel(const std::uint32_t *list_index, std::uint32_t old_n, const std::uint32_t *start,
                             const std::uint32_t *nbr, Real *hist, const std::uint32_t *old_start,
                             const std::uint32_t *old_nbr, const Real *old_hist, unsigned history, std::uint32_t n) {
  const std::uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i < n) engine::carry_history(i, list_index, old_n, start, nbr, hist, old_start, old_nbr, old_hist, history);
}

template <class Real>
__global__ void after_build_kernel(const Real *x, const Real *y, const Real *z, Real *x0, Real *y0, Real *z0,
                                   std::uint32_t *list_index, std::uint32_t n) {
  const std::uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i >= n) return;
  x0[i] = x[i], y0[i] = y[i], z0[i] = z[i];
  list_index[i] = i;
}

// A plane's dense wall records: overlap (0 when apart), its normal and velocity.
template <class Real> struct PlaneArgs { Real point[3], normal[3], velocity[3]; };
template <class Real>
__global__ void plane_kernel(PlaneArgs<Real> pl, const Real *x, const Real *y, const Real *z, const Real *r,
                             std::uint32_t n, WallContacts<Real> w) {
  const std::uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i >= n) return;
  const Real overlap = engine::plane_overlap(pl.point, pl.normal, x[i], y[i], z[i], r[i]);
  w.overlap[i] = overlap > 0 ? overlap : Real(0);
  w.nx[i] = pl.normal[0], w.ny[i] = pl.normal[1], w.nz[i] = pl.normal[2];
  w.vx[i] = pl.velocity[0], w.vy[i] = pl.velocity[1], w.vz[i] = pl.velocity[2];
}

template <class Real>
__global__ void deep_pairs_kernel(ListArgs<Real> a, const std::uint32_t *start, const std::uint32_t *nbr, Real limit,
                                  PassReport *out) {
  const std::uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
  const unsigned bad =
      i < a.n ? engine::deep_overlaps(i, a.x, a.y, a.z, a.r, start, nbr, nullptr, a.len, a.per, limit) : 0u;
  add_report(out, 0.0, 0, 0, bad);
}

template <class Real>
__global__ void deep_wall_kernel(const Real *overlap, const Real *r, Real limit, std::uint32_t n, PassReport *out) {
  const std::uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
  add_report(out, 0.0, 0, 0, i < n && overlap[i] > limit * 2 * r[i] ? 1u : 0u);
}

// A stepper's own stream. Non-blocking: cases that step at once on one GPU, each from a thread of the
// simulate stage's pool, wait neither for one another nor for the legacy default stream.
class Stream {
 public:
  explicit Stream(int device) {
    select_device(device);
    ok(cudaStreamCreateWithFlags(&stream_, cudaStreamNonBlocking), "creating a CUDA stream");
  }
  Stream(const Stream &) = delete;
  Stream &operator=(const Stream &) = delete;
  ~Stream() { cudaStreamDestroy(stream_); }  // its work finishes first
  operator cudaStream_t() const { return stream_; }

 private:
  cudaStream_t stream_ = nullptr;
};

// Device copies of one wall slot's records and history.
template <class Real> struct DeviceSlot {
  DeviceArray<Real> a[7], hist, scratch;  // overlap, nx, ny, nz, vx, vy, vz
  WallContacts<Real> view(std::uint32_t n) {
    return {n, a[0].data(), a[1].data(), a[2].data(), a[3].data(), a[4].data(), a[5].data(), a[6].data(), hist.data()};
  }
};

template <class Real> class ResidentStepper final : public engine::StepBackend<Real> {
  using State = engine::StepState<Real>;

 public:
  ResidentStepper(ResidentLaws laws, int device) : laws_(std::move(laws)), device_(device), stream_(device) {
    report_.resize(1);
    bounds_.resize(1);
  }
  std::string name() const override { return "cuda on " + device_name(device_); }

  void upload(State &state) override {
    select_device(device_);
    auto &p = state.particles;
    n_ = static_cast<std::uint32_t>(p.size());
    real_.clear();
    index_.clear();
    std::size_t k = 0;
    p.for_each_real([&](std::vector<Real> &c) {
      if (real_.size() <= k) real_.emplace_back();
      real_column_[&c] = k;
      real_[k++].upload(c.data(), c.size(), stream_);
    });
    k = 0;
    p.for_each_index([&](std::vector<std::uint32_t> &c) {
      if (index_.size() <= k) index_.emplace_back();
      index_column_[&c] = k;
      index_[k++].upload(c.data(), c.size(), stream_);
    });
    auto &list = state.list;
    // The kernels keep each law's own history; a rolling spring (rolling_model: epsd) adds to it on the
    // CPU only. Refused here, where every caller of the GPU backend passes, not only the scene files'.
    bool fits = engine::law_history(state.pair_law) == laws_.pair.ops->history;
    for (std::size_t w = 0; w < state.planes.size(); ++w)
      fits = fits && state.planes[w].slot.history == laws_.planes.at(w).ops->history;
    for (std::size_t w = 0; w < state.geometries.size(); ++w)
      fits = fits && state.geometries[w].slot.history == laws_.geometries.at(w).second.ops->history;
    if (!fits)
      throw InputError("the rolling spring (rolling_model: epsd) steps on the CPU only: set backend: cpu, "
                       "or rolling_model: constant");
    history_ = laws_.pair.ops->history;
    if (state.list_valid && list.start.size() == std::size_t(n_) + 1) {
      start_.upload(list.start.data(), list.start.size(), stream_);
      nbr_.upload(list.nbr.data(), list.nbr.size(), stream_);
      hist_.upload(list.hist.data(), list.hist.size(), stream_);
    } else {
      state.list_valid = false;
    }
    slots_.clear();
    slots_.resize(state.planes.size() + state.geometries.size());
    std::size_t s = 0;
    auto put = [&](auto &slot) {
      const std::vector<Real> *from[7] = {&slot.overlap, &slot.nx, &slot.ny, &slot.nz, &slot.vx, &slot.vy, &slot.vz};
      for (int q = 0; q < 7; ++q) slots_[s].a[q].upload(from[q]->data(), from[q]->size(), stream_);
      slots_[s].hist.upload(slot.hist.data(), slot.hist.size(), stream_);
      ++s;
    };
    for (auto &pl : state.planes) put(pl.slot);
    for (auto &ge : state.geometries) put(ge.slot);
  }

  void download(State &state) override {
    select_device(device_);
    auto &p = state.particles;
    p.for_each_real([&](std::vector<Real> &c) { real_[real_column_.at(&c)].download(c.data(), stream_); });
    p.for_each_index([&](std::vector<std::uint32_t> &c) { index_[index_column_.at(&c)].download(c.data(), stream_); });
    auto &list = state.list;
    list.start.resize(start_.size());
    list.nbr.resize(nbr_.size());
    list.hist.resize(hist_.size());
    start_.download(list.start.data(), stream_);
    nbr_.download(list.nbr.data(), stream_);
    hist_.download(list.hist.data(), stream_);
    list.restore_mirror(state.pairs_once());
    std::size_t s = 0;
    auto get = [&](auto &slot) {
      std::vector<Real> *to[7] = {&slot.overlap, &slot.nx, &slot.ny, &slot.nz, &slot.vx, &slot.vy, &slot.vz};
      for (int q = 0; q < 7; ++q) slots_[s].a[q].download(to[q]->data(), stream_);
      slots_[s].hist.download(slot.hist.data(), stream_);
      ++s;
    };
    for (auto &pl : state.planes) get(pl.slot);
    for (auto &ge : state.geometries) get(ge.slot);
  }

  void step(State &state) override {
    const auto t0 = std::chrono::steady_clock::now();
    select_device(device_);
    const auto &settings = state.settings;
    auto &counters = state.counters;
    if (!state.list_valid) rebuild(state);
    if (!state.forces_valid) forces(state);
    const Real dt = Real(state.dt), half = Real(0.5 * state.dt);
    // first half kick and drift
    const PassReport first =
        run_reported([&](PassReport *out) { launch_kick_drift(state, half, dt, out); }, "the first half kick");
    if (first.nonfinite > 0) fail_on_host(state, [&] { state.report_bad_particle(); });
    bool rebuild_now = !state.list_valid;
    if (first.escaped > 0) state.leaving = true;  // removed at the next build, as on the CPU
    double largest;
    {
      const unsigned long long bits = first.d2_bits;
      std::memcpy(&largest, &bits, sizeof largest);
    }
    const double half_skin = 0.5 * state.skin;
    rebuild_now = rebuild_now || !(largest <= half_skin * half_skin);
    for (auto &pl : state.planes)
      for (int a = 0; a < 3; ++a) pl.wall.point[a] += state.dt * pl.wall.velocity[a];
    state.time += state.dt;
    ++state.step;
    if (rebuild_now) rebuild(state);
    forces(state);
    const Real limit2 = Real(state.speed_limit * state.speed_limit);  // as the CPU rounds it
    const PassReport second =
        run_reported([&](PassReport *out) { launch_kick_check(state, half, limit2, out); }, "the second half kick");
    if (second.bad > 0) fail_on_host(state, [&] { state.report_bad_particle(); });
    if (state.step % settings.check_every == 0) {
      const PassReport deep = run_reported([&](PassReport *out) { launch_deep(state, out); }, "the overlap check");
      if (deep.bad > 0) fail_on_host(state, [&] { state.report_deep_overlap(deep.bad); });
    }
    ++counters.steps;
    counters.particle_steps += double(n_);
    counters.integrated_particle_steps += double(n_);
    counters.wall_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  }

 private:
  Real *col(std::vector<Real> &c) { return real_[real_column_.at(&c)].data(); }
  std::uint32_t *icol(std::vector<std::uint32_t> &c) { return index_[index_column_.at(&c)].data(); }

  // The host copy up to date, as Simulation::sync_host would (the engine calls download itself).
  void sim_to_host(State &state) { download(state); }
  template <class F> [[noreturn]] void fail_on_host(State &state, F &&report) {
    sim_to_host(state);
    report();
    throw RunFailure("the GPU run stopped at an invalid state");  // report() throws first
  }

  // A small copy on this stepper's stream, waited for: a kernel's fault before it is reported as `what`.
  void copy(void *to, const void *from, std::size_t bytes, cudaMemcpyKind kind, const char *what) {
    ok(cudaMemcpyAsync(to, from, bytes, kind, stream_), what);
    ok(cudaStreamSynchronize(stream_), what);
  }

  template <class Launch> PassReport run_reported(Launch &&launch, const char *what) {
    ok(cudaMemsetAsync(report_.data(), 0, sizeof(PassReport), stream_), "clearing the step report");
    launch(report_.data());
    ok(cudaGetLastError(), what);
    PassReport r;
    copy(&r, report_.data(), sizeof r, cudaMemcpyDeviceToHost, what);
    return r;
  }

  engine::KickDrift<Real> kick_view(State &state, Real half, Real dt) {
    auto &p = state.particles;
    const auto &d = state.domain;
    engine::KickDrift<Real> k{col(p.x),     col(p.y),  col(p.z),  col(p.vx), col(p.vy),    col(p.vz),    col(p.fx),
                              col(p.fy),    col(p.fz), col(p.wx), col(p.wy), col(p.wz),    col(p.tx),    col(p.ty),
                              col(p.tz),    col(p.x0), col(p.y0), col(p.z0), col(p.inv_m), col(p.inv_i), col(p.mobile),
                              half,         dt,        {},        {},        {},           {},           {},
                              state.rotate, false};
    for (int a = 0; a < 3; ++a) {
      k.g[a] = Real(state.settings.gravity[a]);
      k.lo[a] = Real(d.lo[a]);
      k.hi[a] = Real(d.hi[a]);
      k.len[a] = Real(d.length(a));
      k.periodic[a] = d.periodic[a];
    }
    return k;
  }

  void launch_kick_drift(State &state, Real half, Real dt, PassReport *out) {
    const engine::KickDrift<Real> k = kick_view(state, half, dt);
    if (n_ == 0) return;
    engine::with_flags(
        [&]<bool PX, bool PY, bool PZ, bool Rotate>() {
          kick_drift_kernel<Real, PX, PY, PZ, Rotate><<<blocks_for(n_), block_size, 0, stream_>>>(k, n_, out);
        },
        k.periodic[0], k.periodic[1], k.periodic[2], k.rotate);
  }
  void launch_kick_check(State &state, Real half, Real limit2, PassReport *out) {
    const engine::KickDrift<Real> k = kick_view(state, half, Real(state.dt));
    if (n_ == 0) return;
    engine::with_flags(
        [&]<bool Rotate>() {
          kick_check_kernel<Real, Rotate><<<blocks_for(n_), block_size, 0, stream_>>>(k, limit2, n_, out);
        },
        k.rotate);
  }

  ListArgs<Real> list_args(State &state) {
    auto &p = state.particles;
    const auto &d = state.domain;
    ListArgs<Real> a{col(p.x),           col(p.y), col(p.z),         col(p.r), grid_, cell_sorted_.data(),
                     cell_start_.data(), {},       Real(state.skin), {},       n_};
    for (int q = 0; q < 3; ++q) a.len[q] = Real(d.length(q)), a.per[q] = d.periodic[q];
    return a;
  }

  void launch_deep(State &state, PassReport *out) {
    if (n_ == 0) return;
    auto &p = state.particles;
    const Real limit = Real(state.settings.overlap_limit);
    deep_pairs_kernel<Real>
        <<<blocks_for(n_), block_size, 0, stream_>>>(list_args(state), start_.data(), nbr_.data(), limit, out);
    std::size_t s = 0;
    for (auto &pl : state.planes) {
      if (pl.wall.active)
        deep_wall_kernel<Real>
            <<<blocks_for(n_), block_size, 0, stream_>>>(slots_[s].a[0].data(), col(p.r), limit, n_, out);
      ++s;
    }
    for (std::size_t g = 0; g < state.geometries.size(); ++g, ++s)
      deep_wall_kernel<Real>
          <<<blocks_for(n_), block_size, 0, stream_>>>(slots_[s].a[0].data(), col(p.r), limit, n_, out);
  }

  // The engine's rebuild_list, on the device: bounds, grid (the same host function), cells, a stable
  // sort by cell, every column gathered, cell ranges, then the list counted and filled.
  void rebuild(State &state) {
    if (state.leaving) {
      sim_to_host(state);
      state.remove_escaped();
      upload(state);
    }
    auto &p = state.particles;
    const auto &d = state.domain;
    ++state.counters.list_builds;
    state.list_valid = true;
    if (n_ == 0) {
      const std::uint32_t zero = 0;
      start_.upload(&zero, 1, stream_);
      nbr_.resize(0);
      hist_.resize(0);
      return;
    }
    Bounds b{{~0ull, ~0ull, ~0ull}, {0, 0, 0}, 0};
    copy(bounds_.data(), &b, sizeof b, cudaMemcpyHostToDevice, "the bounding box");
    bounds_kernel<Real>
        <<<blocks_for(n_), block_size, 0, stream_>>>(col(p.x), col(p.y), col(p.z), col(p.r), n_, bounds_.data());
    copy(&b, bounds_.data(), sizeof b, cudaMemcpyDeviceToHost, "the bounding box");
    double lo[3], hi[3];
    for (int a = 0; a < 3; ++a) lo[a] = from_ordered(b.lo[a]), hi[a] = from_ordered(b.hi[a]);
    const double reach = 2 * from_ordered(b.r_max) + state.skin;
    for (int a = 0; a < 3; ++a)
      if (d.periodic[a] && d.length(a) < 2 * reach)
        throw engine::SetupError(
            "domain: the periodic length along " + std::string(1, "xyz"[a]) +
            " must be at least twice the largest diameter + skin; widen the domain or lower the skin");
    grid_ = engine::make_cell_grid<Real>(d, lo, hi, reach, n_);
    const std::size_t cells = grid_.count();

    // a stable sort by cell: the permutation of the CPU's stable counting sort
    cell_.resize(n_), cell_sorted_.resize(n_), perm_in_.resize(n_), perm_.resize(n_);
    cell_kernel<Real><<<blocks_for(n_), block_size, 0, stream_>>>(grid_, col(p.x), col(p.y), col(p.z), n_, cell_.data(),
                                                                  perm_in_.data());
    int bits = 1;
    while (bits < 32 && (std::size_t(1) << bits) < cells) ++bits;
    std::size_t temp_bytes = 0;
    ok(cub::DeviceRadixSort::SortPairs(nullptr, temp_bytes, cell_.data(), cell_sorted_.data(), perm_in_.data(),
                                       perm_.data(), int(n_), 0, bits, stream_),
       "sizing the sort by cell");
    temp_.resize(temp_bytes);
    ok(cub::DeviceRadixSort::SortPairs(temp_.data(), temp_bytes, cell_.data(), cell_sorted_.data(), perm_in_.data(),
                                       perm_.data(), int(n_), 0, bits, stream_),
       "sorting the particles by cell");
    for (auto &c : real_) gather(c, 1);
    for (auto &c : index_) gather(c, 1);
    for (auto &s : slots_) gather(s.hist, s.hist.size() / std::max<std::size_t>(1, n_));

    // cell ranges
    counts_.resize(cells + 1);
    ok(cudaMemsetAsync(counts_.data(), 0, (cells + 1) * sizeof(std::uint32_t), stream_), "counting the cells");
    count_cells_kernel<<<blocks_for(n_), block_size, 0, stream_>>>(cell_sorted_.data(), n_, counts_.data());
    cell_start_.resize(cells + 1);
    exclusive_sum(counts_, cell_start_, cells + 1, "the cell ranges");

    // the list: counted, summed, filled; history carried from the previous list
    std::swap(start_, old_start_);
    std::swap(nbr_, old_nbr_);
    std::swap(hist_, old_hist_);
    const ListArgs<Real> args = list_args(state);
    counts_.resize(std::size_t(n_) + 1);
    ok(cudaMemsetAsync(counts_.data(), 0, (std::size_t(n_) + 1) * sizeof(std::uint32_t), stream_),
       "counting the neighbours");
    list_count_kernel<Real><<<blocks_for(n_), block_size, 0, stream_>>>(args, counts_.data());
    start_.resize(std::size_t(n_) + 1);
    exclusive_sum(counts_, start_, std::size_t(n_) + 1, "the list offsets");
    std::uint32_t entries = 0;
    copy(&entries, start_.data() + n_, sizeof entries, cudaMemcpyDeviceToHost, "the list length");
    nbr_.resize(entries);
    hist_.resize(std::size_t(entries) * history_);
    if (hist_.size() > 0)
      ok(cudaMemsetAsync(hist_.data(), 0, hist_.size() * sizeof(Real), stream_), "clearing the history");
    if (entries > 0)
      list_fill_kernel<Real><<<blocks_for(n_), block_size, 0, stream_>>>(args, start_.data(), nbr_.data());
    const std::size_t old_n = old_start_.size() > 0 ? old_start_.size() - 1 : 0;
    if (history_ > 0 && old_nbr_.size() > 0)
      carry_kernel<Real><<<blocks_for(n_), block_size, 0, stream_>>>(
          icol(p.list_index), std::uint32_t(old_n), start_.data(), nbr_.data(), hist_.data(), old_start_.data(),
          old_nbr_.data(), old_hist_.data(), history_, n_);
    after_build_kernel<Real><<<blocks_for(n_), block_size, 0, stream_>>>(col(p.x), col(p.y), col(p.z), col(p.x0),
                                                                         col(p.y0), col(p.z0), icol(p.list_index), n_);
    ok(cudaGetLastError(), "rebuilding the neighbour list");
  }

  template <class T> void gather(DeviceArray<T> &c, std::size_t stride) {
    if (c.size() == 0 || stride == 0) return;
    DeviceArray<T> &out = scratch_for(c);
    out.resize(c.size());
    gather_kernel<T>
        <<<blocks_for(n_), block_size, 0, stream_>>>(c.data(), out.data(), perm_.data(), n_, unsigned(stride));
    std::swap(c, out);
  }
  DeviceArray<Real> &scratch_for(DeviceArray<Real> &) { return scratch_real_; }
  DeviceArray<std::uint32_t> &scratch_for(DeviceArray<std::uint32_t> &) { return scratch_index_; }

  void exclusive_sum(DeviceArray<std::uint32_t> &in, DeviceArray<std::uint32_t> &out, std::size_t n, const char *what) {
    std::size_t temp_bytes = 0;
    ok(cub::DeviceScan::ExclusiveSum(nullptr, temp_bytes, in.data(), out.data(), int(n), stream_), what);
    temp_.resize(temp_bytes);
    ok(cub::DeviceScan::ExclusiveSum(temp_.data(), temp_bytes, in.data(), out.data(), int(n), stream_), what);
  }

  // Every force and torque of the step: pairs, planes and geometries, in the CPU's order.
  void forces(State &state) {
    auto &p = state.particles;
    state.forces_valid = true;
    if (n_ == 0) return;
    for (std::vector<Real> *c : {&p.fx, &p.fy, &p.fz, &p.tx, &p.ty, &p.tz})
      ok(cudaMemsetAsync(col(*c), 0, std::size_t(n_) * sizeof(Real), stream_), "clearing the force accumulators");
    const auto &d = state.domain;
    Particles<Real> v{n_,        col(p.x),  col(p.y), col(p.z), col(p.vx), col(p.vy),      col(p.vz),       col(p.wx),
                      col(p.wy), col(p.wz), col(p.r), col(p.m), col(p.fx), col(p.fy),      col(p.fz),       col(p.tx),
                      col(p.ty), col(p.tz), {},       {},       {},        Real(state.dt), Real(state.time)};
    for (int a = 0; a < 3; ++a) {
      v.box_lo[a] = Real(d.lo[a]);
      v.box_hi[a] = Real(d.hi[a]);
      v.periodic[a] = d.periodic[a] ? 1 : 0;
    }
    const PairList<Real> list{start_.data(), nbr_.data(), hist_.data()};
    launch_pairs(laws_.pair, state.pair_law.self, v, list, device_, stream_);
    std::size_t s = 0;
    auto &planes = state.planes;
    for (std::size_t k = 0; k < planes.size(); ++k, ++s) {
      const auto &wall = planes[k].wall;
      if (!wall.active) continue;
      PlaneArgs<Real> pl;
      for (int a = 0; a < 3; ++a)
        pl.point[a] = Real(wall.point[a]), pl.normal[a] = Real(wall.normal[a]), pl.velocity[a] = Real(wall.velocity[a]);
      const WallContacts<Real> w = slots_[s].view(n_);
      plane_kernel<Real><<<blocks_for(n_), block_size, 0, stream_>>>(pl, col(p.x), col(p.y), col(p.z), col(p.r), n_, w);
      launch_walls(laws_.planes.at(k), wall.law.self, v, w, device_, stream_);
    }
    auto &geometries = state.geometries;
    for (std::size_t k = 0; k < geometries.size(); ++k, ++s) {
      const WallContacts<Real> w = slots_[s].view(n_);
      Particles<Real> at = v;  // the geometry's own clock (engine/walls.hpp)
      at.t = Real(state.time + geometries[k].geometry.time_shift);
      launch_geometry(laws_.geometries.at(k).first, geometries[k].geometry.self, at, w, device_, stream_);
      launch_walls(laws_.geometries.at(k).second, geometries[k].geometry.law.self, v, w, device_, stream_);
    }
    ok(cudaGetLastError(), "the contact forces");
  }

  ResidentLaws laws_;
  int device_;
  Stream stream_;  // every kernel, copy and sort of this stepper, and the plugins' kernels it launches
  std::uint32_t n_ = 0;
  unsigned history_ = 0;
  std::vector<DeviceArray<Real>> real_;
  std::vector<DeviceArray<std::uint32_t>> index_;
  std::map<const std::vector<Real> *, std::size_t> real_column_;
  std::map<const std::vector<std::uint32_t> *, std::size_t> index_column_;
  std::vector<DeviceSlot<Real>> slots_;  // planes, then geometries
  DeviceArray<std::uint32_t> start_, nbr_, old_start_, old_nbr_;
  DeviceArray<Real> hist_, old_hist_, scratch_real_;
  DeviceArray<std::uint32_t> cell_, cell_sorted_, perm_in_, perm_, counts_, cell_start_, scratch_index_;
  DeviceArray<unsigned char> temp_;
  DeviceArray<PassReport> report_;
  DeviceArray<Bounds> bounds_;
  engine::CellGrid<Real> grid_;
};

}  // namespace

template <class Real>
std::unique_ptr<engine::StepBackend<Real>> make_resident_stepper(const engine::Simulation<Real> &sim, ResidentLaws laws,
                                                                 int device) {
  if (sim.settings().sleep)
    throw InputError(
        "scene.time.sleep: sleeping particles are not on the GPU backend yet; turn time.sleep off "
        "or set scene.backend: cpu");
  if (laws.planes.size() != sim.plane_wall_count() || laws.geometries.size() != sim.geometry_count())
    throw InputError("the GPU backend needs the kernels of every plane wall and geometry of the scene");
  return std::make_unique<ResidentStepper<Real>>(std::move(laws), device);
}

template std::unique_ptr<engine::StepBackend<double>> make_resident_stepper<double>(const engine::Simulation<double> &,
                                                                                    ResidentLaws, int);
template std::unique_ptr<engine::StepBackend<float>> make_resident_stepper<float>(const engine::Simulation<float> &,
                                                                                  ResidentLaws, int);

}  // namespace spreadmap::cuda
