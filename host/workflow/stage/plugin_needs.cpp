#include "workflow/stage/plugin_needs.hpp"

#include <spreadmap/surrogate.hpp>

#include <algorithm>
#include <functional>

#include "core/error.hpp"
#include "core/plugin_abi.hpp"
#include "core/suggest.hpp"
#include "analysis/known_columns.hpp"

namespace spreadmap {
namespace {

// The plugins of `kind` that load, in name order; one that does not load is left out (the stage that
// names it reports why).
std::vector<const LoadedPlugin *> loadable(PluginRegistry &registry, const std::string &kind) {
  std::vector<std::string> names = registry.names(kind);
  std::sort(names.begin(), names.end());
  std::vector<const LoadedPlugin *> out;
  for (const auto &n : names) {
    try {
      out.push_back(&registry.get(kind, n));
    } catch (const Error &) {
    }
  }
  return out;
}

const LoadedPlugin &first_with(PluginRegistry &registry, const std::string &kind, const std::string &who,
                               const std::string &capability, const std::function<bool(const LoadedPlugin &)> &has) {
  std::vector<std::string> seen;
  for (const LoadedPlugin *p : loadable(registry, kind)) {
    if (has(*p)) return *p;
    seen.push_back(p->descriptor->name);
  }
  throw PluginError(who + " needs a " + kind + " plugin that " + capability + "; " +
                    (seen.empty() ? "none is installed" : "of those installed (" + join(seen) + ") none does") +
                    "\n  install one (docs/plugins.md), or name one that does (spreadmap plugins --kind " + kind + ")");
}

std::vector<std::string> contract_names() {
  std::vector<std::string> out;
  for (const auto &c : metric_contract()) out.push_back(c.name);
  return out;
}

}  // namespace

const std::vector<ContractMetric> &metric_contract() {
  static const std::vector<ContractMetric> contract = {
      {spread_rate_column, known_column(spread_rate_column)->unit},
      {roughness_column, known_column(roughness_column)->unit},
  };
  return contract;
}

std::string contract_columns() { return join(contract_names(), ","); }

std::vector<sm_metric_v1> declared_metrics(const LoadedPlugin &metrics) {
  const sm_plugin_v1 &d = *metrics.descriptor;
  if (abi_minor(d) < 2 || !d.ops) return {};
  const auto *ops = static_cast<const sm_metrics_ops_v1 *>(d.ops);
  std::vector<sm_metric_v1> out;
  for (uint32_t k = 0; ops->gives && k < ops->n_gives; ++k)
    if (ops->gives[k].name && ops->gives[k].unit)
      out.push_back({ops->gives[k].name, ops->gives[k].unit, ops->gives[k].doc ? ops->gives[k].doc : ""});
  return out;
}

const LoadedPlugin &contract_metrics_plugin(PluginRegistry &registry, const std::string &who) {
  return first_with(registry, "metrics", who, "declares the metrics " + join(contract_names(), " and "),
                    [](const LoadedPlugin &p) {
    const auto gives = declared_metrics(p);
    return std::all_of(metric_contract().begin(), metric_contract().end(), [&](const ContractMetric &c) {
      return std::any_of(gives.begin(), gives.end(), [&](const sm_metric_v1 &m) {
        return std::string(m.name) == c.name && std::string(m.unit) == c.unit;
      });
    });
  });
}

const LoadedPlugin &surrogate_with_std(PluginRegistry &registry, const std::string &who) {
  return first_with(registry, "surrogate", who, "gives a predictive standard deviation", [](const LoadedPlugin &p) {
    const auto *ops = static_cast<const sm_surrogate_ops_v1 *>(p.descriptor->ops);
    return ops && ops->has_std;
  });
}

std::vector<std::string> every_surrogate(PluginRegistry &registry) {
  std::vector<std::string> out;
  for (const LoadedPlugin *p : loadable(registry, "surrogate")) out.push_back(p->descriptor->name);
  return out;
}

std::string first_surrogate(PluginRegistry &registry, const std::string &who) {
  return first_with(registry, "surrogate", who, "loads", [](const LoadedPlugin &) { return true; }).descriptor->name;
}

}  // namespace spreadmap
