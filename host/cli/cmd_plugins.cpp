// `spreadmap plugins [NAME]`: the plugins found and, for one, its parameter schema.
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <spreadmap/surrogate.hpp>

#include <boost/program_options.hpp>
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>

#include "cli/program_commands.hpp"
#include "core/error.hpp"
#include "core/registry.hpp"
#include "core/schema.hpp"
#include "core/suggest.hpp"
#include "workflow/stage/command_line.hpp"
#include "workflow/stage/plugin_needs.hpp"

namespace spreadmap::cli {

namespace po = boost::program_options;
namespace sm = spreadmap;

namespace {

// What a plugin declares beyond its parameters, by which the stages choose it (plugin_needs.hpp).
nlohmann::json capabilities(const sm::LoadedPlugin &p) {
  nlohmann::json j = nlohmann::json::object();
  const std::string kind = p.descriptor->kind;
  if (kind == "metrics") {
    j["gives"] = nlohmann::json::array();
    for (const auto &m : sm::declared_metrics(p)) j["gives"].push_back({{"name", m.name}, {"unit", m.unit}, {"doc", m.doc}});
  } else if (kind == "surrogate") {
    const auto *ops = static_cast<const sm_surrogate_ops_v1 *>(p.descriptor->ops);
    j["predictive_std"] = ops && ops->has_std;
    j["takes_noise_var"] = ops && ops->takes_noise_var;
  }
  return j;
}

std::string describe_capabilities(const nlohmann::json &c) {
  std::string text;
  if (c.contains("gives")) {
    text += c["gives"].empty() ? "  gives: nothing declared (plugin ABI before 10.2)\n" : "  gives (every evaluation):\n";
    for (const auto &m : c["gives"])
      text += fmt::format("    {:<22} {:<7} {}\n", m["name"].get<std::string>(), m["unit"].get<std::string>(),
                          m["doc"].get<std::string>());
  }
  if (c.contains("predictive_std"))
    text += std::string("  predictive standard deviation: ") + (c["predictive_std"].get<bool>() ? "yes" : "no") +
            "; known noise of replicates: " + (c["takes_noise_var"].get<bool>() ? "used" : "ignored") + "\n";
  return text;
}

}  // namespace

int cmd_plugins(int argc, char **argv) {
  po::options_description d("plugins options");
  std::string kind, name, format = "table";
  Common c;
  d.add_options()("kind", po::value(&kind), "contact | spreader | metrics | surrogate")(
      "name", po::value(&name), "one plugin: print its parameter schema")(
      "format", po::value(&format)->default_value("table"), "table | json");
  c.add(d);
  po::positional_options_description p;
  p.add("name", 1);
  po::variables_map vm;
  if (!parse(argc, argv, d, p, vm, "plugins [--kind KIND] [NAME] [--format table|json]")) return 0;
  c.apply();
  auto &reg = sm::PluginRegistry::global();
  std::vector<std::string> kinds = sm::plugin_kinds();
  if (!kind.empty()) {
    if (std::find(kinds.begin(), kinds.end(), kind) == kinds.end())
      throw sm::InputError("--kind " + kind + ": not a plugin kind (" + sm::join(kinds) + ")");
    kinds = {kind};
  }
  nlohmann::json all = nlohmann::json::array();
  bool found = false;
  for (const auto &k : kinds) {
    for (const auto &n : reg.names(k)) {
      if (!name.empty() && n != name) continue;
      found = true;
      const sm::LoadedPlugin *loaded = nullptr;
      try {
        loaded = &reg.get(k, n);
      } catch (const sm::PluginError &e) {
        if (!name.empty()) throw;
        spdlog::warn("{} (skipped; the other plugins are listed)", e.what());  // one broken library hides nothing else
        continue;
      }
      const auto &pl = *loaded;
      if (format == "json") {
        auto j = sm::schema_json(*pl.descriptor);
        j["file"] = pl.file.string();
        j.update(capabilities(pl));
        all.push_back(j);
      } else if (name.empty()) {
        std::printf("%-10s %-16s %-8s %s\n", k.c_str(), n.c_str(), pl.descriptor->version, pl.descriptor->summary);
      } else {
        std::cout << sm::describe_schema(*pl.descriptor) << describe_capabilities(capabilities(pl))
                  << "  file: " << pl.file.string() << "\n";
      }
    }
  }
  if (!name.empty() && !found) {
    std::vector<std::string> every;
    for (const auto &k : kinds)
      for (const auto &n : reg.names(k)) every.push_back(n);
    const std::string near = sm::closest(name, every);
    throw sm::InputError("no plugin named '" + name + "'" +
                         (near.empty() ? "" : "; did you mean '" + near + "'?") + " available: " + sm::join(every));
  }
  if (format == "json") std::cout << all.dump(2) << "\n";
  return 0;
}

}  // namespace spreadmap::cli
