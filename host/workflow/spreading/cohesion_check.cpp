#include "workflow/spreading/cohesion_check.hpp"

#include <fmt/format.h>

#include <exception>
#include <numbers>
#include <nlohmann/json.hpp>
#include <yaml-cpp/yaml.h>

#include "engine/plugin_law.hpp"
#include "engine/stability.hpp"
#include "workflow/spreading/powder_cost.hpp"

namespace spreadmap {
namespace {

// Where a key of the user's file is: the key, else its section, else the file's scene.
Location where(const YAML::Node &user, const std::string &file, const char *section, const char *key) {
  const YAML::Node sec = section ? user[section] : user;
  if (sec && sec.IsMap() && sec[key]) return Location::of(file, sec[key]);
  return Location::of(file, sec ? sec : user);
}

// What `ask` answers of the scene's law bound with `params` (the engine's view of it).
template <class Ask>
auto of_bound_law(PluginRegistry &registry, const Scene &scene, const nlohmann::json &params, Ask ask) {
  const PluginInstance law(registry.get("contact", scene.contact.use), params.dump(), "scene.contact");
  return ask(engine::bound_law(law));
}

// The critical step of a law bound with `params` between bodies of m_eq and r_eff [s]; 0: none is stable.
double critical_step(PluginRegistry &registry, const Scene &scene, const nlohmann::json &params, double m_eq,
                     double r_eff) {
  return of_bound_law(registry, scene, params,
                      [&](const engine::ContactLaw &law) { return engine::contact_critical_dt(law, m_eq, r_eff); });
}

// SJKR softens a linear contact by 2 pi k_c r_eff; where that reaches its stiffness every contact
// collapses and no step is stable. Checked for the smallest spheres, two of them and one on the plate,
// with the largest k_c that still leaves a step (bisection over the law's own answer).
void check_stable_step(const Scene &scene, const YAML::Node &user, const std::string &file, PluginRegistry &registry,
                       Diagnostics &diag) {
  const double d = estimate_case_cost(scene, registry).smallest;  // after coarse graining
  const double m = scene.powder.density * std::numbers::pi / 6 * d * d * d;
  const struct {
    const nlohmann::json &params;
    const char *section, *pair;
    double m_eq, r_eff;
  } contacts[] = {{scene.contact.params, "contact", "two of the smallest spheres", m / 2, d / 4},
                  {scene.substrate.law, "substrate", "the smallest sphere on the plate", m, d / 2}};
  for (const auto &c : contacts) {
    if (critical_step(registry, scene, c.params, c.m_eq, c.r_eff) > 0) continue;
    const double k_c = c.params.value("cohesion_energy_density", 0.0);
    double lo = 0, hi = k_c;  // lo leaves a step, hi does not
    for (int k = 0; k < 40 && k_c > 0; ++k) {
      nlohmann::json p = c.params;
      p["cohesion_energy_density"] = 0.5 * (lo + hi);
      (critical_step(registry, scene, p, c.m_eq, c.r_eff) > 0 ? lo : hi) = 0.5 * (lo + hi);
    }
    const std::string key = fmt::format("scene.{}.cohesion_energy_density", c.section);
    diag.error(where(user, file, c.section, "cohesion_energy_density"), key,
               fmt::format("no time step is stable: the cohesion's softening cancels the contact's stiffness for {} "
                           "({:.3g} um)",
                           c.pair, d * 1e6),
               k_c > 0 ? fmt::format("lower cohesion_energy_density below {:.3g} J/m^3, stiffen the law (a larger "
                                     "v_max / overlap_max), or leave the finest particles out (powder.d_min)",
                                     lo)
                       : std::string("lower the cohesion or stiffen the law (a larger v_max / overlap_max)"));
  }
}

// A particle or substrate law that attracts across a gap (it declares a range: the cohesion part's
// hamaker_constant) steps on the CPU without sleeping: the engine would refuse it at the first step.
void check_gap_attraction(const Scene &scene, const YAML::Node &user, const std::string &file, PluginRegistry &registry,
                          Diagnostics &diag) {
  auto reaches = [&](const nlohmann::json &params) {
    return of_bound_law(registry, scene, params, &engine::law_range) > 0;
  };
  if (!reaches(scene.contact.params) && !reaches(scene.substrate.law)) return;
  if (scene.backend == "cuda")
    diag.error(where(user, file, nullptr, "backend"), "scene.backend",
               "backend: cuda cannot run van der Waals attraction across a gap (hamaker_constant): it steps on the "
               "CPU only",
               "set backend: auto or cpu, or hamaker_constant: 0");
  if (scene.time.sleep)
    diag.error(where(user, file, "time", "sleep"), "scene.time.sleep",
               "sleep cannot run with van der Waals attraction across a gap (hamaker_constant): a sleeping sphere "
               "would be pulled without moving",
               "set time: {sleep: false}, or hamaker_constant: 0");
}

}  // namespace

void check_cohesion(const Scene &scene, const YAML::Node &user, const std::string &file, PluginRegistry &registry,
                    Diagnostics &diag) {
  // A law or size the earlier checks refused throws here: reported there already.
  try {
    check_stable_step(scene, user, file, registry, diag);
  } catch (const std::exception &) {
  }
  try {
    check_gap_attraction(scene, user, file, registry, diag);
  } catch (const std::exception &) {
  }
}

}  // namespace spreadmap
