// A fixed random packing of spheres for comparing and timing backends: a jittered simple-cubic
// lattice compressed so that most lattice neighbours overlap by about 1 % of a diameter (some stay
// apart, within the skin), random velocities and spins, periodic in x and y, with its full
// (both-direction) CSR neighbour list in ascending neighbour order and random contact history.
// Used by tests/gpu, tests/unit/cuda_* and bench/gpu_*; the same seed gives the same packing.
#pragma once
#include <spreadmap/batch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <stdexcept>
#include <vector>

namespace spreadmap::test {

struct PackingSpec {
  std::uint32_t n = 2000;
  double radius = 125e-6;       // mean radius [m]
  double spread = 0.2;          // radii uniform in radius * [1 - spread/2, 1 + spread/2]
  double compression = 0.012;   // lattice spacing = 2 radius (1 - compression)
  double jitter = 0.01;         // positions moved by up to +-jitter * spacing along each axis
  double speed = 0.2;           // velocity components uniform in +-speed [m/s]
  double spin = 300;            // angular velocity components uniform in +-spin [rad/s]
  double history = 2e-6;        // history values uniform in +-history (spring elongations [m])
  double skin = 0.1;            // list cutoff = r_i + r_j + skin * 2 radius
  double density = 4430;        // [kg/m^3]
  double dt = 1e-7;             // [s]
  unsigned history_values = 3;  // per pair entry and per wall record
  std::uint64_t seed = 20240917;
};

template <class Real> struct Packing {
  std::uint32_t n = 0;
  std::vector<Real> x, y, z, vx, vy, vz, wx, wy, wz, r, m, fx, fy, fz, tx, ty, tz;
  std::vector<std::uint32_t> start, nbr;
  std::vector<Real> hist;  // history_values per list entry
  Real box_lo[3] = {0, 0, 0}, box_hi[3] = {0, 0, 0};
  Real dt = 0, t = 0;

  Particles<Real> particles() {
    Particles<Real> p{};
    p.n = n;
    p.x = x.data();
    p.y = y.data();
    p.z = z.data();
    p.vx = vx.data();
    p.vy = vy.data();
    p.vz = vz.data();
    p.wx = wx.data();
    p.wy = wy.data();
    p.wz = wz.data();
    p.r = r.data();
    p.m = m.data();
    p.fx = fx.data();
    p.fy = fy.data();
    p.fz = fz.data();
    p.tx = tx.data();
    p.ty = ty.data();
    p.tz = tz.data();
    for (int a = 0; a < 3; ++a) {
      p.box_lo[a] = box_lo[a];
      p.box_hi[a] = box_hi[a];
    }
    p.periodic[0] = 1;
    p.periodic[1] = 1;
    p.periodic[2] = 0;
    p.dt = dt;
    p.t = t;
    return p;
  }
  PairList<Real> pairs() { return {start.data(), nbr.data(), hist.data()}; }
  void clear_accumulators() {
    for (auto *a : {&fx, &fy, &fz, &tx, &ty, &tz}) std::fill(a->begin(), a->end(), Real(0));
  }
  std::size_t entries() const { return nbr.size(); }
};

namespace detail {
inline double wrapped(double d, double length) { return d - length * std::round(d / length); }
}  // namespace detail

template <class Real> Packing<Real> make_packing(const PackingSpec &s) {
  Packing<Real> k;
  k.n = s.n;
  std::mt19937_64 rng(s.seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const auto side = static_cast<std::uint32_t>(std::ceil(std::cbrt(double(s.n))));
  const double a = 2 * s.radius * (1 - s.compression);
  const double length = side * a;
  k.box_lo[0] = k.box_lo[1] = 0;
  k.box_hi[0] = k.box_hi[1] = Real(length);
  k.box_lo[2] = Real(-a);
  k.box_hi[2] = Real(length + a);
  k.dt = Real(s.dt);
  for (auto *v : {&k.x, &k.y, &k.z, &k.vx, &k.vy, &k.vz, &k.wx, &k.wy, &k.wz, &k.r, &k.m, &k.fx, &k.fy, &k.fz, &k.tx,
                  &k.ty, &k.tz})
    v->assign(s.n, Real(0));
  std::vector<double> px(s.n), py(s.n), pz(s.n), pr(s.n);
  for (std::uint32_t i = 0; i < s.n; ++i) {
    const std::uint32_t ix = i % side, iy = i / side % side, iz = i / (side * side);
    px[i] = (ix + 0.5) * a + s.jitter * a * u(rng);
    py[i] = (iy + 0.5) * a + s.jitter * a * u(rng);
    pz[i] = (iz + 0.5) * a + s.jitter * a * u(rng);
    pr[i] = s.radius * (1 + 0.5 * s.spread * u(rng));
    k.x[i] = Real(px[i]);
    k.y[i] = Real(py[i]);
    k.z[i] = Real(pz[i]);
    k.r[i] = Real(pr[i]);
    k.m[i] = Real(s.density * 4.0 / 3.0 * 3.14159265358979323846 * pr[i] * pr[i] * pr[i]);
    k.vx[i] = Real(s.speed * u(rng));
    k.vy[i] = Real(s.speed * u(rng));
    k.vz[i] = Real(s.speed * u(rng));
    k.wx[i] = Real(s.spin * u(rng));
    k.wy[i] = Real(s.spin * u(rng));
    k.wz[i] = Real(s.spin * u(rng));
  }
  // Cell binning: cells at least one cutoff wide, neighbours from the 27 cells around (x, y wrap).
  const double r_max = s.radius * (1 + 0.5 * s.spread);
  const double cutoff = 2 * r_max + s.skin * 2 * s.radius;
  const int nc = std::max(1, int(length / cutoff)), ncz = std::max(1, int((length + a) / cutoff));
  if (nc < 3)
    throw std::invalid_argument("make_packing: at least 3 cells across the periodic box are needed; use n >= 64");
  const double cell = length / nc, cell_z = (length + a) / ncz;
  auto cell_of = [&](std::uint32_t i, int &cx, int &cy, int &cz) {
    cx = std::min(nc - 1, int(px[i] / cell));
    cy = std::min(nc - 1, int(py[i] / cell));
    cz = std::clamp(int(pz[i] / cell_z), 0, ncz - 1);
  };
  std::vector<std::vector<std::uint32_t>> cells(std::size_t(nc) * nc * ncz);
  for (std::uint32_t i = 0; i < s.n; ++i) {
    int cx, cy, cz;
    cell_of(i, cx, cy, cz);
    cells[(std::size_t(cz) * nc + cy) * nc + cx].push_back(i);
  }
  k.start.assign(std::size_t(s.n) + 1, 0);
  std::vector<std::uint32_t> found;
  for (std::uint32_t i = 0; i < s.n; ++i) {
    int cx, cy, cz;
    cell_of(i, cx, cy, cz);
    found.clear();
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int zz = cz + dz;
          if (zz < 0 || zz >= ncz) continue;
          const int xx = (cx + dx + nc) % nc, yy = (cy + dy + nc) % nc;
          for (std::uint32_t j : cells[(std::size_t(zz) * nc + yy) * nc + xx]) {
            if (j == i) continue;
            const double ddx = detail::wrapped(px[i] - px[j], length), ddy = detail::wrapped(py[i] - py[j], length);
            const double ddz = pz[i] - pz[j], reach = pr[i] + pr[j] + s.skin * 2 * s.radius;
            if (ddx * ddx + ddy * ddy + ddz * ddz < reach * reach) found.push_back(j);
          }
        }
    std::sort(found.begin(), found.end());
    k.nbr.insert(k.nbr.end(), found.begin(), found.end());
    k.start[i + 1] = static_cast<std::uint32_t>(k.nbr.size());
  }
  k.hist.resize(k.nbr.size() * s.history_values);
  for (auto &h : k.hist) h = Real(s.history * u(rng));
  return k;
}

// Dense wall records over the packing: about half the particles touch, with random unit normals,
// overlaps up to 1 % of the radius and wall velocities up to 0.1 m/s; random history.
template <class Real> struct WallRecords {
  std::vector<Real> overlap, nx, ny, nz, vx, vy, vz, hist;
  WallContacts<Real> view() {
    return {static_cast<std::uint32_t>(overlap.size()),
            overlap.data(),
            nx.data(),
            ny.data(),
            nz.data(),
            vx.data(),
            vy.data(),
            vz.data(),
            hist.data()};
  }
};

template <class Real> WallRecords<Real> make_wall_records(const Packing<Real> &k, const PackingSpec &s) {
  WallRecords<Real> w;
  std::mt19937_64 rng(s.seed + 1);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (auto *v : {&w.overlap, &w.nx, &w.ny, &w.nz, &w.vx, &w.vy, &w.vz}) v->assign(k.n, Real(0));
  for (std::uint32_t i = 0; i < k.n; ++i) {
    double n[3] = {u(rng), u(rng), u(rng)};
    double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (len < 1e-3) n[0] = n[1] = 0, n[2] = len = 1;
    w.nx[i] = Real(n[0] / len);
    w.ny[i] = Real(n[1] / len);
    w.nz[i] = Real(n[2] / len);
    w.overlap[i] = Real(0.01 * s.radius * u(rng));  // <= 0: not touching
    w.vx[i] = Real(0.1 * u(rng));
    w.vy[i] = Real(0.1 * u(rng));
    w.vz[i] = Real(0.1 * u(rng));
  }
  w.hist.resize(std::size_t(k.n) * s.history_values);
  for (auto &h : w.hist) h = Real(s.history * u(rng));
  return w;
}

}  // namespace spreadmap::test
