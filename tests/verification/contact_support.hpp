// Test support for contact laws: schema-default parameter values, and a minimal integrator for a few
// spheres and plane walls that drives a law through the SDK's own per-particle bodies (pair_forces_on,
// wall_force_on: the contact-point kinematics and torque arms are the engine's, the bits its queues give). Velocity Verlet with the forces
// evaluated at the new positions and the half-step velocities (translation and spin), as the engine
// does: v += a dt/2; x += v dt; F(x, v); v += a dt/2. The law sees the state in `Real` (double or
// float, as the engine's precisions); the integrator keeps it in double.
#pragma once
#include <spreadmap/contact.hpp>
#include <spreadmap/params.hpp>

#include <nlohmann/json.hpp>
#include <algorithm>
#include <vector>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace spreadmap::test {

using V3 = Vec3<double>;

// Every schema default filled in (as the host does), then `overrides` on top.
template <class Law> Values values_for(const nlohmann::json &overrides = nlohmann::json::object()) {
  nlohmann::json j = nlohmann::json::object();
  for (const sm_param_v1 &p : Law::params) {
    if (p.required) continue;
    switch (p.type) {
      case SM_NUMBER:
        j[p.name] = p.def;
        break;
      case SM_INTEGER:
        j[p.name] = static_cast<long>(p.def);
        break;
      case SM_BOOLEAN:
        j[p.name] = p.def != 0;
        break;
      case SM_ENUM:
      case SM_STRING:
        j[p.name] = p.def_text;
        break;
      case SM_TABLE:
        break;
    }
  }
  for (const auto &[key, value] : overrides.items()) j[key] = value;
  return Values(j);
}
template <class Law> Law bind_law(const nlohmann::json &overrides = nlohmann::json::object()) {
  return Law::bind(values_for<Law>(overrides));
}

struct Sphere {
  V3 x, v, w;
  double r, m;
  double inertia() const { return 0.4 * m * r * r; }
};

struct Plane {
  V3 point, normal;  // normal: unit, pointing into the side where the spheres are
};

template <class Law, class Real = double> class Integrator {
 public:
  Integrator(const Law &law, std::vector<Sphere> spheres, double dt, V3 gravity = {0, 0, 0},
             std::vector<Plane> walls = {})
      : law_(law), s_(std::move(spheres)), walls_(std::move(walls)), dt_(dt), g_(gravity) {
#ifdef _OPENMP
    // One or two spheres: the SDK loops' parallel regions would only add per-step thread wake-ups,
    // which cost milliseconds on a loaded 2-core machine.
    omp_set_num_threads(1);
#endif
    const std::size_t n = s_.size();
    for (auto *a : {&x_, &y_, &z_, &vx_, &vy_, &vz_, &wx_, &wy_, &wz_, &r_, &m_, &fx_, &fy_, &fz_, &tx_, &ty_, &tz_})
      a->assign(n, 0.0);
    start_.push_back(0);
    for (std::uint32_t i = 0; i < n; ++i) {  // full list: everyone else, in index order
      for (std::uint32_t j = 0; j < n; ++j)
        if (j != i) nbr_.push_back(j);
      start_.push_back(static_cast<std::uint32_t>(nbr_.size()));
    }
    const std::size_t history = std::max(history_of(law_), 1);
    pair_hist_.assign(nbr_.size() * history, 0.0);
    wall_hist_.assign(walls_.size(), std::vector<Real>(n * history, Real(0)));
    for (auto *a : {&w_overlap_, &w_nx_, &w_ny_, &w_nz_, &w_vx_, &w_vy_, &w_vz_}) a->assign(n, 0.0);
    compute_forces();
  }

  void step() {
    kick();
    for (auto &s : s_) s.x += s.v * dt_;
    t_ += dt_;
    compute_forces();
    kick();
  }

  // A constant external torque on sphere i [N m], added at every kick from now on.
  void set_external_torque(std::size_t i, V3 t) {
    external_torque_.resize(s_.size(), V3{0, 0, 0});
    external_torque_[i] = t;
  }

  // A constant external force on sphere i [N] (a pull or a load), added at every kick from now on.
  void set_external_force(std::size_t i, V3 f) {
    external_.resize(s_.size(), V3{0, 0, 0});
    external_[i] = f;
  }

  const std::vector<Sphere> &spheres() const { return s_; }
  Sphere &sphere(std::size_t i) { return s_[i]; }
  V3 force(std::size_t i) const { return {double(fx_[i]), double(fy_[i]), double(fz_[i])}; }
  V3 torque(std::size_t i) const { return {double(tx_[i]), double(ty_[i]), double(tz_[i])}; }
  double time() const { return t_; }
  double dt() const { return dt_; }
  // Overlap of sphere i with wall k (> 0 in contact) or with sphere j.
  double wall_overlap(std::size_t i, std::size_t k = 0) const {
    return s_[i].r - dot(s_[i].x - walls_[k].point, walls_[k].normal);
  }
  double pair_overlap(std::size_t i, std::size_t j) const { return s_[i].r + s_[j].r - norm(s_[i].x - s_[j].x); }

 private:
  void kick() {
    for (std::size_t i = 0; i < s_.size(); ++i) {
      Sphere &s = s_[i];
      s.v += (force(i) * (1 / s.m) + g_) * (0.5 * dt_);
      if (!external_.empty()) s.v += external_[i] * (0.5 * dt_ / s.m);
      s.w += torque(i) * (0.5 * dt_ / s.inertia());
      if (!external_torque_.empty()) s.w += external_torque_[i] * (0.5 * dt_ / s.inertia());
    }
  }
  void compute_forces() {
    const std::size_t n = s_.size();
    for (std::size_t i = 0; i < n; ++i) {
      const Sphere &s = s_[i];
      x_[i] = Real(s.x.x);
      y_[i] = Real(s.x.y);
      z_[i] = Real(s.x.z);
      vx_[i] = Real(s.v.x);
      vy_[i] = Real(s.v.y);
      vz_[i] = Real(s.v.z);
      wx_[i] = Real(s.w.x);
      wy_[i] = Real(s.w.y);
      wz_[i] = Real(s.w.z);
      r_[i] = Real(s.r);
      m_[i] = Real(s.m);
      fx_[i] = fy_[i] = fz_[i] = tx_[i] = ty_[i] = tz_[i] = 0;
    }
    Particles<Real> p{static_cast<std::uint32_t>(n),
                      x_.data(),
                      y_.data(),
                      z_.data(),
                      vx_.data(),
                      vy_.data(),
                      vz_.data(),
                      wx_.data(),
                      wy_.data(),
                      wz_.data(),
                      r_.data(),
                      m_.data(),
                      fx_.data(),
                      fy_.data(),
                      fz_.data(),
                      tx_.data(),
                      ty_.data(),
                      tz_.data(),
                      {-1, -1, -1},
                      {1, 1, 1},
                      {0, 0, 0},
                      Real(dt_),
                      Real(t_)};
    PairList<Real> list{start_.data(), nbr_.data(), pair_hist_.data()};
    in_loop_form<LoopForms::whole_list>(law_, [&](const auto &form) {
      for (std::uint32_t i = 0; i < p.n; ++i) pair_forces_on(form, p, list, i);
    });
    for (std::size_t k = 0; k < walls_.size(); ++k) {
      for (std::size_t i = 0; i < n; ++i) {
        w_overlap_[i] = Real(wall_overlap(i, k));
        w_nx_[i] = Real(walls_[k].normal.x);
        w_ny_[i] = Real(walls_[k].normal.y);
        w_nz_[i] = Real(walls_[k].normal.z);
      }
      WallContacts<Real> w{static_cast<std::uint32_t>(n),
                           w_overlap_.data(),
                           w_nx_.data(),
                           w_ny_.data(),
                           w_nz_.data(),
                           w_vx_.data(),
                           w_vy_.data(),
                           w_vz_.data(),
                           wall_hist_[k].data()};
      w.gap = Real(1);  // the records hold every gap exactly: a law reaching across one sees it up to its range
      in_loop_form<LoopForms::whole_list>(law_, [&](const auto &form) {
        for (std::uint32_t i = 0; i < w.n; ++i) wall_force_on(form, p, w, i);
      });
    }
  }

  Law law_;
  std::vector<Sphere> s_;
  std::vector<Plane> walls_;
  double dt_, t_ = 0;
  V3 g_;
  std::vector<V3> external_, external_torque_;  // empty: none
  std::vector<Real> x_, y_, z_, vx_, vy_, vz_, wx_, wy_, wz_, r_, m_, fx_, fy_, fz_, tx_, ty_, tz_;
  std::vector<std::uint32_t> start_, nbr_;
  std::vector<Real> pair_hist_;
  std::vector<std::vector<Real>> wall_hist_;
  std::vector<Real> w_overlap_, w_nx_, w_ny_, w_nz_, w_vx_, w_vy_, w_vz_;
};

// A 250 um Ti-6Al-4V sphere, the study's particle.
inline Sphere study_sphere(V3 x = {0, 0, 0}, V3 v = {0, 0, 0}, V3 w = {0, 0, 0}) {
  const double r = 125e-6, m = 4430.0 * 4.0 / 3.0 * pi * r * r * r;
  return {x, v, w, r, m};
}

}  // namespace spreadmap::test
