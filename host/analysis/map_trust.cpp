#include "map_trust.hpp"
#include "analysis/known_columns.hpp"

#include <fmt/format.h>

#include <cmath>
#include <nlohmann/json.hpp>

namespace spreadmap::analysis {

namespace {
double number(const nlohmann::json &j, const char *key) {
  const auto it = j.find(key);
  return it != j.end() && it->is_number() ? it->get<double>() : std::numeric_limits<double>::quiet_NaN();
}
}  // namespace

nlohmann::json MapTrust::to_json() const {
  const auto value = [](double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(); };
  const char *word = verdict == Verdict::trusted ? "trusted" : verdict == Verdict::untrusted ? "untrusted" : "unknown";
  return {{"verdict", word},      {"q2_cv", value(q2_cv)},     {"r_cv", value(r_cv)},
          {"nrmse_cv", value(nrmse_cv)}, {"rmse_cv", value(rmse_cv)}, {"min_q2_cv", min_trusted_q2_cv},
          {"reason", reason}};
}

std::vector<MapTrust> judge_map_trust(const ModelFile &model) {
  const nlohmann::json report = model.training.value("report", nlohmann::json::object());
  const nlohmann::json outputs = report.value("outputs", nlohmann::json::array());
  std::vector<MapTrust> out;
  for (const auto &v : model.outputs) {
    MapTrust t;
    t.output = v.name;
    for (const auto &o : outputs)
      if (o.is_object() && o.value("name", "") == v.name) {
        t.q2_cv = number(o, "q2_cv"), t.r_cv = number(o, "r_cv");
        t.nrmse_cv = number(o, "nrmse_cv"), t.rmse_cv = number(o, "rmse_cv");
      }
    if (!std::isfinite(t.q2_cv)) {
      t.verdict = MapTrust::Verdict::unknown;
      t.reason = "no cross-validated Q^2 in model.json (too few rows to cross-validate, or an older train stage)";
    } else {
      t.verdict = t.q2_cv >= min_trusted_q2_cv ? MapTrust::Verdict::trusted : MapTrust::Verdict::untrusted;
      t.reason = fmt::format("cross-validated Q^2 = {:.2f} ({} {:.2f}; R_cv {:.2f}, NRMSE_cv {:.1f} %)", t.q2_cv,
                             t.untrusted() ? "below" : "at least", min_trusted_q2_cv, t.r_cv, t.nrmse_cv);
    }
    out.push_back(std::move(t));
  }
  return out;
}

std::vector<std::string> trust_notes(const std::vector<MapTrust> &trust) {
  std::vector<std::string> notes;
  for (const auto &t : trust)
    if (t.untrusted() && is_contract_metric(t.output))
      notes.push_back(fmt::format("{} map NOT TRUSTED: cross-validated Q^2 = {:.2f} < {:.2f}", known_symbol(t.output),
                                  t.q2_cv, min_trusted_q2_cv));
  return notes;
}

}  // namespace spreadmap::analysis
