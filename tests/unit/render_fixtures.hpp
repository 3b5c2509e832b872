// Small fixed inputs for the figure tests and the reference images (deterministic: no <random>
// distributions, whose output differs between standard libraries).
#pragma once

#include <spreadmap/render/figures.hpp>

#include <cmath>
#include <cstdint>

namespace spreadmap::render::testing {

// Uniform in [0, 1) from a 64-bit LCG.
struct Lcg {
  std::uint64_t state;
  double next() {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return static_cast<double>(state >> 11) * (1.0 / 9007199254740992.0);
  }
};

// A heap of `count` 250 um spheres in front of a 10 mm roller on a 40 x 2.5 mm strip.
inline SnapshotInput heap_snapshot(int count = 2000, double roller_angle = 0.6) {
  SnapshotInput s;
  s.domain.lo = {0, 0, 0};
  s.domain.hi = {0.04, 0.0025, 0.012};
  Lcg g{42};
  for (int i = 0; i < count; ++i) {
    const double x = 0.006 + 0.012 * g.next(), y = 0.000125 + 0.00225 * g.next();
    const double h = 0.004 * std::sin(3.14159265358979 * (x - 0.006) / 0.012);
    s.x.push_back(x);
    s.y.push_back(y);
    s.z.push_back(0.000125 + h * g.next());
    s.r.push_back(0.000125);
    s.speed.push_back(0.1 * std::exp(-(x - 0.016) * (x - 0.016) / 1e-5) * g.next());
  }
  for (int k = 0; k < 72; ++k) {  // a 10 mm roller's disc
    s.spreader.outline_x.push_back(0.005 * std::cos(2 * 3.14159265358979 * k / 72));
    s.spreader.outline_z.push_back(0.005 * std::sin(2 * 3.14159265358979 * k / 72));
  }
  s.spreader.reference = {0.021, 0.00125, 0.0055};
  s.spreader.y_centre = 0.00125;
  s.spreader.length = 0.07;
  s.spreader.turns = true;
  s.spreader.angle = roller_angle;
  return s;
}

// A 10 x 2.5 mm layer of 50 um cells: a 0.5 mm mean with bumps of +-60 um.
inline HeightmapInput layer_heightmap() {
  HeightmapInput h;
  h.nx = 200;
  h.ny = 50;
  h.origin = {0.014, 0.0};
  h.cell = {50e-6, 50e-6};
  for (int j = 0; j < h.ny; ++j)
    for (int i = 0; i < h.nx; ++i)
      h.height.push_back(5e-4 + 6e-5 * std::sin(i * 0.21) * std::cos(j * 0.33) + (i == 10 && j == 10 ? NAN : 0.0));
  return h;
}

// Smooth stand-ins for the study's fields over U = 40..100 mm/s, omega = -20..20 rad/s (SI).
inline double vs_model(double u, double w) { return u * (5.0e-4 + 4.0e-6 * w); }                 // m^2/s
inline double rq_model(double u, double w) { return 9e-5 + 0.25e-3 * (u - 0.04) - 0.5e-6 * w; }  // m
inline double rq_std_model(double u, double w) { return 1e-6 + 2e-6 * std::hypot((u - 0.07) / 0.03, w / 20); }

inline std::vector<double> axis(double lo, double hi, int n) {
  std::vector<double> v;
  for (int i = 0; i < n; ++i) v.push_back(lo + (hi - lo) * i / (n - 1));
  return v;
}

inline std::vector<DesignPoint> design(bool roughness) {
  std::vector<DesignPoint> pts;
  int k = 0;
  for (double u : {0.040, 0.055, 0.070, 0.085, 0.100})
    for (double w : {-20.0, -15.0, -10.0, -5.0, 0.0, 5.0, 10.0, 15.0, 20.0}) {
      const double wobble = 1.0 + 0.03 * std::sin(7.0 * k);
      pts.push_back({u, w, (roughness ? rq_model(u, w) : vs_model(u, w)) * wobble, k % 9 == 4 || k % 7 == 3});
      ++k;
    }
  return pts;
}

inline SurfaceInput roughness_surface() {
  SurfaceInput s;
  s.quantity = {"R_q", "m"};
  s.u = axis(0.04, 0.1, 31);
  s.omega = axis(-20, 20, 21);
  for (double w : s.omega)
    for (double u : s.u) s.values.push_back(rq_model(u, w));
  s.points = design(true);
  return s;
}

inline ParityInput two_output_parity() {
  ParityInput p;
  for (bool rough : {false, true}) {
    ParityPanel panel;
    panel.quantity = rough ? PlottedQuantity{"R_q", "m"} : PlottedQuantity{"V_s", "m^2/s"};
    for (const auto& d : design(rough)) {
      const double truth = d.value, predicted = rough ? rq_model(d.u, d.omega) : vs_model(d.u, d.omega);
      (d.test ? panel.test_simulated : panel.train_simulated).push_back(truth);
      (d.test ? panel.test_predicted : panel.train_predicted).push_back(predicted);
    }
    p.panels.push_back(panel);
  }
  return p;
}

inline MapInput process_map_input(bool with_std = true) {
  MapInput m;
  m.u = axis(0.04, 0.1, 61);
  m.omega = axis(-20, 20, 41);
  for (double w : m.omega)
    for (double u : m.u) {
      m.vs.push_back(vs_model(u, w));
      m.rq.push_back(rq_model(u, w));
      if (with_std) m.rq_std.push_back(rq_std_model(u, w));
    }
  m.rq_target = 100e-6;
  // Frontier: for each omega, the largest U whose R_q is within the target.
  for (double w : m.omega) {
    const double u = std::min(0.1, 0.04 + (m.rq_target - 9e-5 + 0.5e-6 * w) / 0.25e-3);
    if (u >= 0.04) m.frontier.push_back({u, w});
  }
  double best = -1;
  for (const auto& p : m.frontier)
    if (vs_model(p.u, p.omega) > best) {
      best = vs_model(p.u, p.omega);
      m.optimum = {true, p.u, p.omega, best, rq_model(p.u, p.omega)};
    }
  return m;
}

}  // namespace spreadmap::render::testing
