// The report's sections about the run's inputs and simulations: the scene, the cases with their
// metrics and snapshots, and the provenance.
#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <fstream>
#include <thread>

#include <spreadmap/abi.h>
#include <nlohmann/json.hpp>

#include "core/plugin_abi.hpp"
#include "core/units.hpp"
#include "core/files.hpp"
#include "workflow/map/mapping.hpp"
#include "workflow/report/html.hpp"
#include "workflow/report/report_sections.hpp"
#include "analysis/known_columns.hpp"

namespace spreadmap::report {

using nlohmann::json;

namespace {
void flatten(const json &j, const std::string &prefix, html::HtmlTable &table) {
  if (j.is_object()) {
    for (const auto &[k, v] : j.items()) flatten(v, prefix.empty() ? k : prefix + "." + k, table);
    return;
  }
  std::string text = j.is_string() ? j.get<std::string>() : j.dump();
  if (text.size() > 160) text = text.substr(0, 157) + "...";
  table.add({html::escape(prefix), html::escape(text)});
}

std::string cpu_model() {
  std::ifstream in("/proc/cpuinfo");
  for (std::string line; std::getline(in, line);)
    if (line.rfind("model name", 0) == 0) return line.substr(line.find(':') + 2);
  return "unknown processor";
}

std::string host_name() {
  char name[256] = {};
  return ::gethostname(name, sizeof name - 1) == 0 ? name : "unknown host";
}
}  // namespace

PageSection scene_section(const json &manifest) {
  std::string body;
  const std::string file = member(manifest, "workflow").value("file", "");
  if (!file.empty() && fs::is_regular_file(file))
    body += "<h3>The workflow as written</h3>\n<pre>" + html::escape(read_text(file)) + "</pre>\n";
  if (manifest.contains("scene") && manifest["scene"].is_object()) {
    html::HtmlTable table({"key", "value (SI: m, s, kg, Pa, N)"}, "keys");
    flatten(manifest["scene"], "", table);
    body += "<details><summary>The scene as resolved, every key (SI units)</summary>\n<div class=\"scroll\">" +
            table.str() + "</div></details>\n";
  }
  return {"scene", "Scene and powder", body};
}

PageSection cases_section(const fs::path &run, const json &manifest) {
  const json cases = member(manifest, "cases");
  if (cases.empty()) return {"cases", "Cases", ""};
  const auto metrics = read_table(run / "metrics.csv");
  std::vector<std::string> inputs, shown_metrics;
  for (const auto &[k, v] : member(cases.front(), "inputs").items()) inputs.push_back(k);
  for (const char *m : {spread_rate_column, roughness_column, "packing_fraction", "coverage"})
    if (metrics && metrics->has_column(m)) shown_metrics.push_back(m);
  std::vector<std::string> header = {"case"};
  for (const auto &k : inputs) header.push_back(k);
  header.insert(header.end(), {"status", "wall time"});
  for (const auto &m : shown_metrics) header.push_back(metric_label(m));
  header.push_back("snapshot");
  html::HtmlTable table(header);
  const std::vector<std::string> metric_ids = metrics ? metrics->texts("case") : std::vector<std::string>();
  std::vector<std::vector<double>> metric_columns;
  for (const auto &m : shown_metrics) metric_columns.push_back(metrics->numbers(m));
  for (const auto &c : cases) {
    const std::string id = c.value("id", "");
    std::vector<std::string> row = {html::escape(id)};
    for (const auto &k : inputs) row.push_back(html::escape(shown(member(c, "inputs").value(k, json()), unit_of(k))));
    row.push_back(html::escape(c.value("status", "pending")));
    row.push_back(c.contains("wall_seconds") ? number(field(c, "wall_seconds"), "{:.0f} s") : "");
    const auto at = std::find(metric_ids.begin(), metric_ids.end(), id);
    for (std::size_t k = 0; k < shown_metrics.size(); ++k)
      row.push_back(at == metric_ids.end()
                        ? ""
                        : html::escape(display(metric_columns[k][std::size_t(at - metric_ids.begin())],
                                               unit_of(shown_metrics[k]))));
    row.push_back(html::inline_png(run / "cases" / id / "snapshot.png", "snapshot of " + id, "thumb"));
    table.add(std::move(row));
  }
  std::string body = paragraph(fmt::format("{} cases; the layer metrics are measured over the sampling region of "
                                           "each spread layer (metrics.csv).",
                                           cases.size()));
  body += "<div class=\"scroll\">" + table.str() + "</div>\n";
  return {"cases", "Cases, their layers and snapshots", body};
}

PageSection provenance_section(const fs::path &run, const json &manifest) {
  html::HtmlTable table({"what", "value"}, "keys");
  table.add({"spreadmap", html::escape(std::string(SPREADMAP_VERSION) + " (plugin ABI " +
                                       host_abi_text() + ")")});
  const json wf = member(manifest, "workflow");
  const std::string file = wf.value("file", "");
  table.add({"workflow", html::escape(file)});
  if (!file.empty() && fs::is_regular_file(file)) table.add({"workflow hash", html::escape(stable_hash(read_text(file)))});
  for (const auto &[stage, t] : member(manifest, "stages").items())
    table.add({html::escape("stage " + stage),
               html::escape(number(field(t, "wall_seconds"), "{:.1f} s") + " (its last run), ended " + t.value("end", ""))});
  for (const auto &[plugin, version] : member(manifest, "plugins").items())
    table.add({html::escape(plugin), html::escape(version.is_string() ? version.get<std::string>() : version.dump())});
  for (const auto &model_dir : {run / "train"})
    if (fs::is_directory(model_dir))
      for (const auto &m : fs::directory_iterator(model_dir)) {
        const json model = read_json(m.path() / "model.json");
        if (model.is_object())
          table.add({html::escape("surrogate " + m.path().filename().string()),
                     html::escape(model.value("plugin", "") + " " + model.value("plugin_version", ""))});
      }
  table.add({"machine", html::escape(fmt::format("{}: {}, {} hardware threads", host_name(), cpu_model(),
                                                 std::thread::hardware_concurrency()))});
  table.add({"run directory", html::escape(fs::absolute(run).string())});
  return {"provenance", "Provenance", "<div class=\"scroll\">" + table.str() + "</div>\n"};
}

}  // namespace spreadmap::report
