#include <algorithm>
#include <engine/errors.hpp>
#include <engine/particle_set.hpp>

#include <cmath>
#include <fmt/format.h>
#include <spreadmap/sphere.hpp>

namespace spreadmap::engine {

namespace {
void check_length(const std::vector<double> &c, const char *name, std::size_t n, bool optional,
                  const std::string &what) {
  if (c.size() == n || (optional && c.empty())) return;
  throw SetupError(fmt::format("{}: column '{}' has {} entries but x has {}; give every column one value per particle",
                               what, name, c.size(), n));
}
void check_finite(const std::vector<double> &c, const char *name, const std::string &what, bool positive) {
  for (std::size_t i = 0; i < c.size(); ++i) {
    if (!std::isfinite(c[i]) || (positive && !(c[i] > 0)))
      throw SetupError(fmt::format("{}: particle {} has {} = {}; it must be {}", what, i, name, c[i],
                                   positive ? "a finite number > 0" : "a finite number"));
  }
}
}  // namespace

void ParticleSet::validate(const std::string &what) const {
  const std::size_t n = x.size();
  check_length(y, "y", n, false, what);
  check_length(z, "z", n, false, what);
  check_length(radius, "radius", n, false, what);
  for (auto [c, name] :
       {std::pair{&vx, "vx"}, {&vy, "vy"}, {&vz, "vz"}, {&wx, "wx"}, {&wy, "wy"}, {&wz, "wz"}, {&mass, "mass"}})
    check_length(*c, name, n, true, what);
  if (!id.empty() && id.size() != n)
    throw SetupError(fmt::format("{}: column 'id' has {} entries but x has {}", what, id.size(), n));
  if (!fixed.empty() && fixed.size() != n)
    throw SetupError(fmt::format("{}: column 'fixed' has {} entries but x has {}", what, fixed.size(), n));
  for (auto [c, name] : {std::pair{&x, "x"},
                         {&y, "y"},
                         {&z, "z"},
                         {&vx, "vx"},
                         {&vy, "vy"},
                         {&vz, "vz"},
                         {&wx, "wx"},
                         {&wy, "wy"},
                         {&wz, "wz"}})
    check_finite(*c, name, what, false);
  check_finite(radius, "radius", what, true);
  check_finite(mass, "mass", what, true);
}

void ParticleSet::fill_defaults(double density, std::uint32_t first_id) {
  const std::size_t n = x.size();
  for (auto *c : {&vx, &vy, &vz, &wx, &wy, &wz})
    if (c->empty()) c->assign(n, 0.0);
  if (mass.empty() && density > 0) {
    mass.resize(n);
    for (std::size_t i = 0; i < n; ++i) mass[i] = sphere_mass(density, radius[i]);
  }
  if (id.empty()) {
    id.resize(n);
    for (std::size_t i = 0; i < n; ++i) id[i] = first_id + static_cast<std::uint32_t>(i);
  }
}

std::vector<double> ParticleSet::kinematics_by_id() const {
  std::vector<std::size_t> order(size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return id[a] < id[b]; });
  std::vector<double> out;
  out.reserve(9 * order.size());
  for (std::size_t i : order)
    for (const auto *c : {&x, &y, &z, &vx, &vy, &vz, &wx, &wy, &wz}) out.push_back((*c)[i]);
  return out;
}

}  // namespace spreadmap::engine
