#include "powder/rough_substrate.hpp"

#include <spreadmap/random.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace sm = spreadmap;
using sm::powder::HeightField;

namespace {

// Kernel exp(-2 (k spacing)^2 / xi^2) for k = -m..m, m covering 3 xi.
std::vector<double> kernel(double spacing, double xi) {
  const auto m = static_cast<long>(std::ceil(3 * xi / spacing));
  std::vector<double> w;
  for (long k = -m; k <= m; ++k) w.push_back(std::exp(-2 * std::pow(k * spacing / xi, 2)));
  return w;
}

// out[i] = sum_k w[k] in[i + k] along one axis of a row-major n_fast x n_slow array; `along_fast`
// picks the axis. Non-periodic: `in` has margin (w.size() / 2) extra points at each end of that
// axis and `out` does not. Periodic: indices wrap, same size.
std::vector<double> convolve(const std::vector<double> &in, std::size_t n_out, std::size_t n_other, bool along_fast,
                             const std::vector<double> &w, bool periodic) {
  const long m = static_cast<long>(w.size() / 2);
  const std::size_t n_in = periodic ? n_out : n_out + 2 * static_cast<std::size_t>(m);
  std::vector<double> out(n_out * n_other, 0.0);
  for (std::size_t o = 0; o < n_other; ++o)
    for (std::size_t i = 0; i < n_out; ++i) {
      double sum = 0;
      for (long k = -m; k <= m; ++k) {
        long j = static_cast<long>(i) + k + (periodic ? 0 : m);
        if (periodic) j = ((j % static_cast<long>(n_in)) + static_cast<long>(n_in)) % static_cast<long>(n_in);
        const std::size_t at =
            along_fast ? o * n_in + static_cast<std::size_t>(j) : static_cast<std::size_t>(j) * n_other + o;
        sum += w[static_cast<std::size_t>(k + m)] * in[at];
      }
      (along_fast ? out[o * n_out + i] : out[i * n_other + o]) = sum;
    }
  return out;
}

}  // namespace

HeightField sm::powder::gaussian_height_field(std::size_t nx, std::size_t ny, double dx, double dy, double rq, double xi,
                                             bool periodic_y, std::uint64_t seed) {
  if (nx == 0 || ny == 0 || !(dx > 0) || !(dy > 0) || !std::isfinite(dx) || !std::isfinite(dy))
    throw std::invalid_argument("rough substrate: the lattice is empty");
  if (!(rq >= 0) || !std::isfinite(rq)) throw std::invalid_argument("rough substrate: rq must be >= 0");
  if (!(xi >= 2 * std::max(dx, dy)) || !std::isfinite(xi))
    throw std::invalid_argument("rough substrate: correlation length " + std::to_string(xi * 1e6) +
                                " um is below 2 lattice spacings (" + std::to_string(2 * std::max(dx, dy) * 1e6) +
                                " um)");
  const auto wx = kernel(dx, xi), wy = kernel(dy, xi);
  const std::size_t mx = wx.size() / 2, my = wy.size() / 2;
  const std::size_t nx_in = nx + 2 * mx, ny_in = periodic_y ? ny : ny + 2 * my;
  Random random(seed);
  std::vector<double> noise(nx_in * ny_in);
  for (double &v : noise) v = random.normal();
  // along x (rows of nx_in points), then along y (columns of nx points)
  const auto rows = convolve(noise, nx, ny_in, true, wx, false);
  HeightField f{nx, ny, dx, dy, convolve(rows, ny, nx, false, wy, periodic_y)};
  double mean = 0;
  for (double v : f.h) mean += v;
  mean /= static_cast<double>(f.h.size());
  double sq = 0;
  for (double &v : f.h) v -= mean, sq += v * v;
  const double scale = sq > 0 ? rq / std::sqrt(sq / static_cast<double>(f.h.size())) : 0.0;
  for (double &v : f.h) v *= scale;
  return f;
}

namespace {

// The lattice of spec: nx x ny points spaced d along x and dy along y (width / ny when periodic, so it wraps).
struct Lattice {
  std::size_t nx, ny;
  double dx, dy;
};

Lattice lattice_of(const sm::powder::RoughnessSpec &s) {
  const double d = s.sphere_diameter;
  if (!(d > 0) || !(d <= s.length) || !(d <= s.width))
    throw std::invalid_argument("rough substrate: sphere diameter " + std::to_string(d * 1e6) +
                                " um does not fit the domain");
  const auto nx = static_cast<std::size_t>(std::floor(s.length / d));
  const auto ny = static_cast<std::size_t>(std::floor(s.width / d));
  return {nx, ny, d, s.periodic_y ? s.width / static_cast<double>(ny) : d};
}

// Spheres of diameter lattice.dx at the lattice's cell centres, their tops on `field` shifted so that
// the lowest sphere stands on z = 0.
sm::powder::RoughSubstrate spheres_on(HeightField field, const Lattice &l) {
  sm::powder::RoughSubstrate out;
  out.field = std::move(field);
  out.radius = l.dx / 2;
  const double lowest = *std::min_element(out.field.h.begin(), out.field.h.end());
  double tops = 0;
  for (std::size_t iy = 0; iy < l.ny; ++iy)
    for (std::size_t ix = 0; ix < l.nx; ++ix) {
      const double z = out.radius + out.field.h[iy * l.nx + ix] - lowest;
      out.x.push_back((static_cast<double>(ix) + 0.5) * l.dx);
      out.y.push_back((static_cast<double>(iy) + 0.5) * l.dy);
      out.z.push_back(z);
      tops += z + out.radius;
    }
  out.mean_top = tops / static_cast<double>(out.z.size());
  return out;
}

}  // namespace

sm::powder::RoughSubstrate sm::powder::rough_substrate(const RoughnessSpec &s) {
  const Lattice l = lattice_of(s);
  return spheres_on(gaussian_height_field(l.nx, l.ny, l.dx, l.dy, s.rq, s.correlation_length, s.periodic_y, s.seed), l);
}

HeightField sm::powder::sampled_height_field(const HeightField &map, std::size_t nx, std::size_t ny, double dx,
                                            double dy) {
  if (map.nx < 2 || map.ny < 2 || map.h.size() != map.nx * map.ny || !(map.dx > 0) || !(map.dy > 0))
    throw std::invalid_argument("height map: at least 2 x 2 points on a grid with positive spacings");
  // One coordinate in map cells, wrapped onto the tile [0, n): the cell's first index and the weight of the next.
  auto locate = [](double at, double spacing, std::size_t n) {
    const double period = spacing * static_cast<double>(n);
    double u = std::fmod(at, period) / spacing;
    if (u < 0) u += static_cast<double>(n);
    auto i = static_cast<std::size_t>(std::floor(u));
    if (i >= n) i = n - 1;  // fmod rounding at the period
    return std::pair{i, u - static_cast<double>(i)};
  };
  HeightField out{nx, ny, dx, dy, std::vector<double>(nx * ny)};
  for (std::size_t iy = 0; iy < ny; ++iy) {
    const auto [j, wy] = locate((static_cast<double>(iy) + 0.5) * dy, map.dy, map.ny);
    const std::size_t j1 = (j + 1) % map.ny;
    for (std::size_t ix = 0; ix < nx; ++ix) {
      const auto [i, wx] = locate((static_cast<double>(ix) + 0.5) * dx, map.dx, map.nx);
      const std::size_t i1 = (i + 1) % map.nx;
      const double below = (1 - wx) * map.h[j * map.nx + i] + wx * map.h[j * map.nx + i1];
      const double above = (1 - wx) * map.h[j1 * map.nx + i] + wx * map.h[j1 * map.nx + i1];
      out.h[iy * nx + ix] = (1 - wy) * below + wy * above;
    }
  }
  return out;
}

sm::powder::RoughSubstrate sm::powder::measured_substrate(const HeightField &map, const RoughnessSpec &s) {
  const Lattice l = lattice_of(s);
  return spheres_on(sampled_height_field(map, l.nx, l.ny, l.dx, l.dy), l);
}
