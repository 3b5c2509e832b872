// The answer first: for each roughness target, the setting the map proposes, how likely it meets the
// target, and whether the maps it rests on can be trusted.
#include "workflow/report/html.hpp"
#include "workflow/report/report_sections.hpp"
#include <nlohmann/json.hpp>

namespace spreadmap::report {

using nlohmann::json;

namespace {
std::vector<std::string> optimum_row(const json &o, const json &units) {
  const std::string target = html::escape("≤ " + shown(o.value("rq_max", json()), "m"));
  const std::string confidence = number(field(o, "confidence"), "{:.2f}");
  if (!o.value("found", false)) return {target, "no setting reaches it", "", "", "", confidence, ""};
  std::string setting;
  for (const auto &[k, v] : member(o, "inputs").items())
    setting += (setting.empty() ? "" : ", ") + k + " = " + shown(v, unit_of(k, units));
  std::string rq = shown(o.value("rq", json()), "m");
  if (o.contains("rq_std")) rq += " ± " + shown(o["rq_std"], "m");
  const bool untrusted = !member(o, "rests_on_untrusted").empty();
  return {target,
          html::escape(setting),
          html::escape(shown(o.value("vs", json()), "m^2/s")),
          html::escape(rq),
          number(field(o, "probability"), "{:.2f}"),
          confidence,
          untrusted ? "<span class=\"warn\">rests on an untrusted map</span>" : ""};
}
}  // namespace

PageSection answer_section(const fs::path &run) {
  const json optimum = read_json(run / "map" / "optimum.json");
  if (!optimum.is_object()) return {"answer", "The answer", ""};
  const json units = member(optimum, "units");
  std::string body;
  for (const auto &[name, t] : member(optimum, "trust").items())
    if (t.value("verdict", "") == "untrusted")
      body += warning("The " + metric_label(name) + " map is NOT TRUSTED: " + t.value("reason", "") +
                      ". Its contours, and any optimum resting on it, are the surrogate's guess: simulate more "
                      "cases or replicates before setting a machine by them.");
  html::HtmlTable table({"target R_q", "setting", "V_s", "R_q (± std)", "P(R_q ≤ target)", "confidence asked", ""});
  for (const auto &o : member(optimum, "optima")) table.add(optimum_row(o, units));
  body += "<div class=\"scroll\">" + table.str() + "</div>\n";
  body += paragraph("Each optimum is the largest V_s whose probability of meeting its R_q target, under the "
                    "surrogate's predictive law (" + optimum.value("model", std::string("the model")) +
                    "), is at least the confidence asked; 0.5 chooses by the predicted mean.");
  body += figure(run / "map" / "map.png", "The process map: R_q filled, V_s as lines, the frontier of largest V_s "
                                         "per R_q, the simulated cases and the optimum.");
  return {"answer", "The answer", body};
}

}  // namespace spreadmap::report
