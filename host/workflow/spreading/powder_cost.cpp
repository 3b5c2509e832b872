#include "workflow/spreading/powder_cost.hpp"

#include <fmt/format.h>
#include <spreadmap/contact.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "engine/plugin_law.hpp"
#include "engine/stability.hpp"
#include "powder/heap.hpp"
#include "workflow/spreading/powder_sizes.hpp"
#include "workflow/spreading/case_setup.hpp"
#include "workflow/spreading/coarse_grain.hpp"

namespace spreadmap {
namespace {

constexpr double reference_rate = 1.2e7;  // particle-steps/s: the quickstart on 2 cores

std::string um_3(double d) { return fmt::format("{:.3g}", d * 1e6); }  // 3 significant digits

std::string summary(const CaseCost &c) {
  return fmt::format("{:.2g} particles, dt = {:.3g} s, {:.2g} particle-steps", c.particles, c.step, c.particle_steps());
}

}  // namespace

CaseCost estimate_case_cost(const Scene &given, PluginRegistry &registry) {
  const Scene scene = coarse_grained(given, registry);
  const Powder &powder = scene.powder;
  const powder::SizeDistribution sizes = size_distribution(powder);
  CaseCost c;
  c.particles = powder.volume > 0 ? double(powder::heap_volume_to_count(powder.volume, sizes)) : double(powder.count);
  c.smallest = sizes.lower();
  c.median = sizes.quantile(0.5, powder::FractionBasis::number);
  const PluginInstance law(registry.get("contact", scene.contact.use), scene.contact.params.dump(), "scene.contact");
  const engine::ContactLaw contact = engine::bound_law(law);
  // Two equal spheres: m_eq = m / 2, r_eff = d / 4.
  auto step_for = [&](double d) {
    if (scene.time.step > 0) return scene.time.step;
    const double m = powder.density * std::numbers::pi / 6 * d * d * d;
    return scene.time.safety * engine::packing_critical_dt(contact, m / 2, d / 4);
  };
  c.step = step_for(c.smallest);
  c.step_at_median = step_for(c.median);
  c.simulated_time =
      powder.settle_time + describe_spreader(scene, registry, "scene.spreader").duration + scene.time.relax;
  return c;
}

std::optional<std::string> powder_cost_warning(const Scene &scene, PluginRegistry &registry, const std::string &file) {
  if (scene.powder.distribution == "mono") return std::nullopt;
  const CaseCost now = estimate_case_cost(scene, registry);
  if (!(now.particle_steps() > practical_particle_steps)) return std::nullopt;
  const double ratio = now.step_at_median / now.step;
  std::string text = fmt::format(
      "{}: scene.powder: the size distribution makes a case cost about {:.2g} particle-steps, about {:.0f} h at "
      "{:.2g} particle-steps/s (practical: up to {:.0e}): {:.2g} particles from {} um (median by number {} um); "
      "dt = {:.3g} s, {}; {:.3g} s simulated. Trades:",
      file, now.particle_steps(), now.particle_steps() / reference_rate / 3600, reference_rate,
      practical_particle_steps, now.particles, um_3(now.smallest), um_3(now.median), now.step,
      ratio > 1.01 ? fmt::format("{:.2g} x smaller than particles of the median size would allow", ratio)
                   : std::string("the contact law's step does not depend on the size"),
      now.simulated_time);
  const double k = scene.powder.coarse_grain;
  if (k < 10) {
    Scene coarser = scene;
    coarser.powder.coarse_grain = std::min(10.0, 2 * k);
    text += fmt::format(
        " powder.coarse_grain: {:g} gives {} (each sphere stands for {:g} of the powder's: the "
        "layer's finer detail is lost);",
        coarser.powder.coarse_grain, summary(estimate_case_cost(coarser, registry)),
        std::pow(coarser.powder.coarse_grain, 3));
  }
  const auto sizes = size_distribution(scene.powder);
  if (scene.powder.distribution == "table") {
    text +=
        " or leave the finest rows out of the table (fewer particles, and a longer step where the law's step "
        "depends on the size)";
    return text;
  }
  Scene truncated = scene;
  truncated.powder.d_min = sizes.quantile(0.1, powder::FractionBasis::number);
  text += fmt::format(
      " powder.d_min: {} um (the D10 by number) gives {} (leaves out the finest 10 % of the "
      "particles, {:.2g} % of the powder's volume)",
      um_3(truncated.powder.d_min), summary(estimate_case_cost(truncated, registry)),
      100 * sizes.cdf(truncated.powder.d_min, powder::FractionBasis::volume));
  return text;
}

}  // namespace spreadmap
