// Conformance of every contact law (one typed suite over all of them): no force and no memory when
// apart, equal and opposite forces seen from both sides, the documented restitution, no energy gain
// at eps = 1, rotation invariance and finite output across the schema ranges.
#include "verification/contact_laws.hpp"
#include "verification/contact_support.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

namespace sm = spreadmap;
using sm::test::Integrator;
using sm::test::Sphere;
using sm::test::V3;
using json = nlohmann::json;

namespace {

// Parameters every law needs beyond its defaults (required ones).
template <class Law> json base_params() { return json::object(); }
template <> json base_params<sm::HertzMindlin>() { return {{"youngs_modulus", 1e9}}; }

template <class Law> Law make(json extra = json::object()) {
  json p = base_params<Law>();
  for (const auto &[k, v] : extra.items()) p[k] = v;
  return sm::test::bind_law<Law>(p);
}

// 400 steps per period of the fastest mode at this pair's masses: integration error well below the
// 0.5 % restitution tolerance (measured: < 0.05 %).
template <class Law> double step_for(const Law &law, double m_eq, double r_eff) {
  return sm::pi / law.natural_frequency(m_eq, r_eff) / 400;
}

double kinetic_energy(const std::vector<Sphere> &s) {
  double e = 0;
  for (const Sphere &p : s) e += 0.5 * p.m * sm::dot(p.v, p.v) + 0.5 * p.inertia() * sm::dot(p.w, p.w);
  return e;
}

struct Collision {
  double energy_in = 0;     // kinetic energy before [J]
  double max_mismatch = 0;  // largest |F_0 + F_1| / |F_0| over the steps
};

// Two unequal spheres colliding; runs until they separate. Returns the integrator.
template <class Law> Integrator<Law> collide(const Law &law, V3 v_rel, V3 w0, V3 w1, Collision *out = nullptr) {
  Sphere a = sm::test::study_sphere({0, 0, 0}, v_rel * 0.6, w0);
  Sphere b = sm::test::study_sphere({0, 0, 0}, v_rel * -0.4, w1);
  b.r = 180e-6;
  b.m = a.m * std::pow(b.r / a.r, 3);
  b.x = {a.r + b.r, 0, 0};  // touching along x, a on the left
  const double m_eq = a.m * b.m / (a.m + b.m), r_eff = a.r * b.r / (a.r + b.r);
  Integrator<Law> run(law, {a, b}, step_for(law, m_eq, r_eff));
  if (out) out->energy_in = kinetic_energy(run.spheres());
  bool touched = false;
  for (int k = 0; k < 200000; ++k) {
    run.step();
    const double overlap = run.pair_overlap(0, 1);
    if (overlap > 0) touched = true;
    if (out) {
      const V3 f0 = run.force(0), f1 = run.force(1);
      out->max_mismatch = std::max(out->max_mismatch, sm::norm(f0 + f1) / std::max(sm::norm(f0), 1e-300));
    }
    if (touched && overlap < 0) break;
  }
  EXPECT_TRUE(touched);
  return run;
}

template <class Law> class ContactConformance : public ::testing::Test {};
TYPED_TEST_SUITE(ContactConformance, sm::test::ContactLaws::Types);

TYPED_TEST(ContactConformance, ApartMeansNoForceAndNoMemory) {
  const auto law = make<TypeParam>({{"rolling_friction", 0.1}});
  for (double overlap : {0.0, -1e-6}) {
    sm::ContactState<double> c{{0, 0, 1}, overlap, -0.3, {0.2, 0.1, 0}, {5, 3, 1}, 2e-8, 6e-5, 1e-8};
    double hist[4] = {1e-7, 2e-7, 3e-7, 42};
    const auto f = law(c, hist);
    EXPECT_EQ(f.normal, 0.0);
    EXPECT_EQ(sm::norm(f.tangent), 0.0);
    EXPECT_EQ(sm::norm(f.torque), 0.0);
    for (int q = 0; q < TypeParam::history; ++q) EXPECT_EQ(hist[q], 0.0) << "history cleared";
    EXPECT_EQ(hist[3], 42.0) << "nothing written beyond the declared history";
  }
}

TYPED_TEST(ContactConformance, EqualAndOppositeForcesFromBothSides) {
  // oblique, spinning, unequal spheres: every step the two sides' forces cancel to round-off
  Collision c;
  collide(make<TypeParam>({{"rolling_friction", 0.05}}), V3{0.5, 0.2, -0.1}, V3{0, 300, 100}, V3{-50, 0, 20}, &c);
  EXPECT_LT(c.max_mismatch, 1e-13);
}

TYPED_TEST(ContactConformance, HeadOnRestitutionIsTheParameter) {
  for (double eps : {0.9, 0.5}) {
    const auto law = make<TypeParam>({{"restitution", eps}});
    auto run = collide(law, V3{0.5, 0, 0}, V3{0, 0, 0}, V3{0, 0, 0});
    const double e = (run.spheres()[1].v.x - run.spheres()[0].v.x) / 0.5;
    EXPECT_NEAR(e, eps, 0.005 * eps) << "eps " << eps;
  }
}

TYPED_TEST(ContactConformance, NoEnergyGainAtRestitutionOne) {
  const double tolerance = 1e-3;  // O((dt omega)^2) integration error of the elastic impact
  for (double mu : {0.0, 0.185}) {
    const auto law = make<TypeParam>({{"restitution", 1.0}, {"friction", mu}});
    Collision c;
    auto run = collide(law, V3{0.5, 0.2, -0.1}, V3{0, 300, 100}, V3{-50, 0, 20}, &c);
    const double e_in = c.energy_in, e_out = kinetic_energy(run.spheres());
    EXPECT_LE(e_out, e_in * (1 + tolerance)) << "mu " << mu;
    if (mu == 0) {
      EXPECT_NEAR(e_out / e_in, 1.0, tolerance) << "elastic and frictionless: energy kept";
    }
  }
}

TYPED_TEST(ContactConformance, RotationInvariance) {
  const auto law = make<TypeParam>({{"rolling_friction", 0.1}});
  // a rotation about an oblique axis (Rodrigues)
  const V3 k = V3{1, -2, 3} * (1 / std::sqrt(14.0));
  const double a = 0.7, ca = std::cos(a), sa = std::sin(a);
  auto rot = [&](V3 v) { return v * ca + sm::cross(k, v) * sa + k * (sm::dot(k, v) * (1 - ca)); };
  const V3 n = V3{0.3, 0.4, std::sqrt(0.75)};
  const V3 v_t0 = sm::cross(n, V3{0.02, -0.01, 0.03});
  const V3 hist_t = sm::cross(n, V3{1e-8, 2e-8, 0});  // an elongation in the tangent plane
  sm::ContactState<double> c{n, 1e-6, -0.05, v_t0, {10, -20, 5}, 2e-8, 6e-5, 5e-8};
  sm::ContactState<double> r = c;
  r.normal = rot(c.normal);
  r.v_t = rot(c.v_t);
  r.w_rel = rot(c.w_rel);
  for (int steps = 0; steps < 3; ++steps) {  // a few steps so that the history is exercised
    double h1[3] = {hist_t.x, hist_t.y, hist_t.z};
    const V3 rh = rot(hist_t);
    double h2[3] = {rh.x, rh.y, rh.z};
    for (int s = 0; s <= steps; ++s) {
      const auto f = law(c, h1), g = law(r, h2);
      const double scale = std::abs(f.normal);
      EXPECT_NEAR(g.normal, f.normal, 1e-12 * scale);
      EXPECT_LT(sm::norm(g.tangent - rot(f.tangent)), 1e-12 * scale);
      EXPECT_LT(sm::norm(g.torque - rot(f.torque)), 1e-12 * scale * c.r_eff + 1e-30);
    }
    const V3 hr = rot(V3{h1[0], h1[1], h1[2]});
    for (int q = 0; q < TypeParam::history; ++q)
      EXPECT_NEAR(h2[q], (&hr.x)[q], 1e-12 * sm::norm(hr)) << "history rotates with the contact";
  }
}

// Every number at its min and max, every enum choice, every boolean flipped (one at a time): bind()
// either refuses with ParamError or the law gives finite forces over extreme contact states, in
// double and in float.
TYPED_TEST(ContactConformance, FiniteAcrossTheSchemaRanges) {
  std::vector<json> variants{json::object()};
  for (const sm_param_v1 &p : TypeParam::params) {
    if (p.type == SM_NUMBER) {
      variants.push_back({{p.name, p.min}});
      variants.push_back({{p.name, p.max}});
    } else if (p.type == SM_BOOLEAN) {
      variants.push_back({{p.name, p.def == 0}});
    } else if (p.type == SM_ENUM) {
      std::string all = p.choices;
      for (std::size_t at = 0; at != std::string::npos;) {
        const std::size_t bar = all.find('|', at);
        variants.push_back({{p.name, all.substr(at, bar == std::string::npos ? bar : bar - at)}});
        at = bar == std::string::npos ? bar : bar + 1;
      }
    }
  }
  int bound = 0;
  for (const json &v : variants) {
    SCOPED_TRACE(v.dump());
    TypeParam law{};
    try {
      law = make<TypeParam>(v);
    } catch (const sm::ParamError &) {
      continue;  // a cross-parameter constraint, reported to the user with a sentence
    }
    ++bound;
    EXPECT_TRUE(std::isfinite(law.natural_frequency(1e-8, 1e-4)) && law.natural_frequency(1e-8, 1e-4) > 0);
    EXPECT_TRUE(std::isfinite(law.damping_ratio(1e-8, 1e-4)));
    for (double overlap : {1e-15, 1e-9, 1e-5})
      for (double v_t : {0.0, 1e-18, 10.0})
        for (double w : {0.0, 1e4})
          for (double m : {1e-12, 1e-3}) {
            const sm::ContactState<double> c{{0, 1, 0}, overlap, -5, {v_t, 0, 0}, {w, 0, w}, m, 1e-4, 1e-7};
            double hd[3] = {1e-6, 0, 0};
            const auto f = law(c, hd);
            EXPECT_TRUE(std::isfinite(f.normal) && std::isfinite(sm::norm(f.tangent)) &&
                        std::isfinite(sm::norm(f.torque)));
            const sm::ContactState<float> cf{
                {0, 1, 0}, float(overlap), -5, {float(v_t), 0, 0}, {float(w), 0, float(w)}, float(m), 1e-4f, 1e-7f};
            float hf[3] = {1e-6f, 0, 0};
            const auto g = law(cf, hf);
            EXPECT_TRUE(std::isfinite(g.normal) && std::isfinite(sm::norm(g.tangent)) &&
                        std::isfinite(sm::norm(g.torque)));
            for (int q = 0; q < TypeParam::history; ++q) EXPECT_TRUE(std::isfinite(hd[q]) && std::isfinite(hf[q]));
          }
  }
  EXPECT_GE(bound, static_cast<int>(variants.size()) - 2) << "only genuine cross-parameter refusals";
}

}  // namespace
