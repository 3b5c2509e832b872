// What a stage asks of a plugin it was not given the name of: a capability the plugin declares, never
// its name, so installing another plugin of a kind is all it takes for the stages to use it. Each
// choice is the first plugin in name order that has the capability; none is an error saying what was
// asked for and how to give it.
#pragma once
#include <spreadmap/metric.hpp>

#include <string>
#include <vector>

#include "core/registry.hpp"

namespace spreadmap {

// The metrics the stages after characterise read (map, verify, adaptive design, report): the metric
// contract every default metrics plugin meets.
struct ContractMetric {
  const char *name, *unit;
};
const std::vector<ContractMetric> &metric_contract();
std::string contract_columns();  // "vs,rq"

// The metrics a plugin declares it gives whatever its parameters (ABI 10.2; none before). Entries
// without a name or unit are left out, a missing doc reads as empty.
std::vector<sm_metric_v1> declared_metrics(const LoadedPlugin &metrics);

// The metrics plugin whose declared metrics hold the contract, with the contract's units.
const LoadedPlugin &contract_metrics_plugin(PluginRegistry &registry, const std::string &who);

// A surrogate that gives a predictive standard deviation with its mean (the adaptive design and the
// calibration place their next runs by it).
const LoadedPlugin &surrogate_with_std(PluginRegistry &registry, const std::string &who);

// Every surrogate that loads, in name order: what the train stage trains when it is not told.
std::vector<std::string> every_surrogate(PluginRegistry &registry);
// The first of them: the model of `spreadmap train` and of a map when neither is told.
std::string first_surrogate(PluginRegistry &registry, const std::string &who);

}  // namespace spreadmap
