// The forms a law's loops are compiled in (LoopForm, in_loop_form in contact.hpp): which one a law's
// parameters choose, and that the form without rolling friction gives the very bits of the constant
// torque's form at mu_r = 0 (its torque is zero there; the form only skips the work), as each of
// HookeSlider's own forms (its slider kinds) gives the bits of the loop that reads the kind per contact.
#include <spreadmap/contact_parts.hpp>

#include "plugins/contact/hertz_mindlin/hertz_mindlin.hpp"
#include "plugins/contact/hooke_history/hooke_history.hpp"
#include "plugins/contact/hooke_slider/hooke_slider.hpp"
#include "verification/contact_support.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <random>
#include <type_traits>
#include <vector>

namespace sm = spreadmap;

namespace {

// The rolling form in_loop_form chooses for a law, for the loops of `Forms`.
template <sm::LoopForms Forms, class Law> sm::RollingForm chosen_form(const Law &law) {
  return sm::in_loop_form<Forms>(law, [](const auto &form) { return std::decay_t<decltype(form)>::rolling; });
}

template <class Law> void expect_forms_follow_the_rolling_friction(const nlohmann::json &base) {
  auto with = [&](const nlohmann::json &more) {
    nlohmann::json p = base;
    p.update(more);
    return sm::test::bind_law<Law>(p);
  };
  const Law none = with({{"rolling_friction", 0.0}}), constant = with({{"rolling_friction", 0.1}}),
            spring = with({{"rolling_friction", 0.1}, {"rolling_model", "epsd"}}),
            spring_off = with({{"rolling_friction", 0.0}, {"rolling_model", "epsd"}});
  using sm::LoopForms;
  EXPECT_EQ(chosen_form<LoopForms::queues>(none), sm::RollingForm::none);
  EXPECT_EQ(chosen_form<LoopForms::queues>(constant), sm::RollingForm::constant);
  EXPECT_EQ(chosen_form<LoopForms::queues>(spring), sm::RollingForm::spring);
  EXPECT_EQ(chosen_form<LoopForms::queues>(spring_off), sm::RollingForm::none) << "epsd at mu_r = 0: no spring";
  // the whole-list loops keep the spring and compute the constant torque whatever the friction
  EXPECT_EQ(chosen_form<LoopForms::whole_list>(none), sm::RollingForm::constant);
  EXPECT_EQ(chosen_form<LoopForms::whole_list>(spring), sm::RollingForm::spring);
  // the kernels are compiled for the constant torque's form alone, whatever the friction
  EXPECT_EQ(chosen_form<LoopForms::kernels>(none), sm::RollingForm::constant);
  EXPECT_EQ(chosen_form<LoopForms::kernels>(spring), sm::RollingForm::constant);
}

TEST(ContactLoopForms, TheRollingFrictionChoosesTheForm) {
  expect_forms_follow_the_rolling_friction<sm::HookeSlider>(nlohmann::json::object());
  expect_forms_follow_the_rolling_friction<sm::HookeHistory>(nlohmann::json::object());
  expect_forms_follow_the_rolling_friction<sm::HertzMindlin>({{"youngs_modulus", 5e7}});
}

// Random contacts of 250 um spheres, touching and (a tenth) just apart, sliding, rolling and spinning.
std::vector<sm::ContactState<double>> random_contacts(int n) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> unit(-1, 1), overlap(-0.3e-6, 3e-6);
  std::vector<sm::ContactState<double>> contacts(n);
  for (auto &c : contacts) {
    sm::Vec3<double> normal{unit(rng), unit(rng), unit(rng)};
    normal = normal * (1 / sm::norm(normal));
    c.normal = normal;
    c.overlap = overlap(rng);
    c.v_n = 0.2 * unit(rng);
    const sm::Vec3<double> slip{0.05 * unit(rng), 0.05 * unit(rng), 0.05 * unit(rng)};
    c.v_t = slip - normal * sm::dot(slip, normal);
    c.w_rel = {300 * unit(rng), 300 * unit(rng), 300 * unit(rng)};
    c.m_eq = 1.8e-8 * (1 + 0.5 * unit(rng));
    c.r_eff = 62.5e-6 * (1 + 0.5 * unit(rng));
    c.dt = 7.5e-7;
  }
  return contacts;
}

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// The forms without rolling friction and with the constant torque, at mu_r = 0: equal bits, history
// included.
template <class Law> void expect_no_rolling_form_keeps_the_bits(const nlohmann::json &params) {
  const Law law = sm::test::bind_law<Law>(params);
  ASSERT_EQ(law.rolling.mu_r, 0.0);
  const sm::LoopForm<Law, false, sm::RollingForm::none> skipped{law};
  const sm::LoopForm<Law, false, sm::RollingForm::constant> computed{law};
  int touching = 0;
  std::vector<double> h1(Law::history + 1, 0.0), h2(Law::history + 1, 0.0);
  for (const auto &c : random_contacts(2000)) {
    const auto a = skipped(c, h1.data()), b = computed(c, h2.data());
    touching += c.overlap > 0;
    EXPECT_TRUE(same_bits(a.normal, b.normal));
    for (auto [x, y] : {std::pair{a.tangent.x, b.tangent.x}, std::pair{a.tangent.y, b.tangent.y},
                        std::pair{a.tangent.z, b.tangent.z}, std::pair{a.torque.x, b.torque.x},
                        std::pair{a.torque.y, b.torque.y}, std::pair{a.torque.z, b.torque.z}})
      EXPECT_TRUE(same_bits(x, y));
    for (int q = 0; q < Law::history; ++q) EXPECT_TRUE(same_bits(h1[q], h2[q]));
  }
  EXPECT_GT(touching, 1500);
}

TEST(ContactLoopForms, WithoutRollingFrictionTheSkippedPartChangesNoBit) {
  expect_no_rolling_form_keeps_the_bits<sm::HookeSlider>({{"slider", "viscous"}});
  expect_no_rolling_form_keeps_the_bits<sm::HookeSlider>({{"slider", "stick"}});
  expect_no_rolling_form_keeps_the_bits<sm::HookeHistory>(nlohmann::json::object());
  expect_no_rolling_form_keeps_the_bits<sm::HertzMindlin>({{"youngs_modulus", 5e7}});
}

// HookeSlider's own forms, its slider kinds: each chosen by the slider parameter, and each giving the
// bits of the loop that reads the kind per contact.
sm::ContactForce<double> force_of(const auto &form, const sm::ContactState<double> &c) {
  return form(c, static_cast<double *>(nullptr));
}

template <int Own> void expect_own_form_keeps_the_bits(const sm::HookeSlider &law) {
  const sm::LoopForm<sm::HookeSlider, false, sm::RollingForm::none, Own> compiled{law};
  const sm::LoopForm<sm::HookeSlider, false, sm::RollingForm::none, sm::any_own_form> read{law};
  int acting = 0;
  for (const auto &c : random_contacts(2000)) {
    const auto a = force_of(compiled, c), b = force_of(read, c);
    acting += a.tangent.x != 0;
    EXPECT_TRUE(same_bits(a.normal, b.normal));
    EXPECT_TRUE(same_bits(a.tangent.x, b.tangent.x) && same_bits(a.tangent.y, b.tangent.y) &&
                same_bits(a.tangent.z, b.tangent.z));
  }
  EXPECT_GT(acting, 1500) << "the slider acts on the touching contacts";
}

TEST(ContactLoopForms, TheSliderIsCompiledIntoHookeSlidersLoopsWithTheSameBits) {
  const char *names[] = {"stick", "viscous", "coulomb"};
  for (int kind = 0; kind < 3; ++kind) {
    const auto law = sm::test::bind_law<sm::HookeSlider>({{"slider", names[kind]}});
    auto own_form = [&]<sm::LoopForms Forms>() {
      return sm::in_loop_form<Forms>(law, [](const auto &form) { return std::decay_t<decltype(form)>::own_form; });
    };
    EXPECT_EQ(own_form.template operator()<sm::LoopForms::queues>(), kind) << names[kind];
    EXPECT_EQ(own_form.template operator()<sm::LoopForms::whole_list>(), sm::any_own_form) << "read per contact";
    EXPECT_EQ(own_form.template operator()<sm::LoopForms::kernels>(), sm::any_own_form) << "read per contact";
  }
  expect_own_form_keeps_the_bits<0>(sm::test::bind_law<sm::HookeSlider>({{"slider", "stick"}}));
  expect_own_form_keeps_the_bits<1>(sm::test::bind_law<sm::HookeSlider>({{"slider", "viscous"}}));
  expect_own_form_keeps_the_bits<2>(sm::test::bind_law<sm::HookeSlider>({{"slider", "coulomb"}}));
}

}  // namespace
