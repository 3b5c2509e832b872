// The report's sections about what was learnt from the cases: each surrogate's accuracy (the study's
// Table 4 form with cross-validation) and parity plots, the response surfaces, the verification.
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "analysis/map_trust.hpp"
#include "workflow/report/html.hpp"
#include "workflow/report/report_sections.hpp"
#include "analysis/known_columns.hpp"

namespace spreadmap::report {

using nlohmann::json;

namespace {
std::string percent(const json &o, const char *key) { return number(field(o, key), "{:.2f} %"); }
std::string r(const json &o, const char *key) { return number(field(o, key), "{:.3f}"); }

std::string verdict(const json &o) {
  const double q2 = field(o, "q2_cv");
  if (!std::isfinite(q2)) return "not judged";
  return q2 >= analysis::min_trusted_q2_cv ? "trusted" : "<span class=\"warn\">NOT trusted</span>";
}

std::string model_scores(const fs::path &dir) {
  const json report = read_json(dir / "report.json");
  if (!report.is_object()) return "";
  html::HtmlTable table({"output", "NRMSE train", "NRMSE test", "NRMSE cross-validated (± sd over folds)", "R train",
                     "R test", "R cross-validated", "Q² cross-validated", "map"});
  for (const auto &o : member(report, "outputs"))
    table.add({html::escape(metric_label(o.value("name", ""))), percent(o, "nrmse_train"), percent(o, "nrmse_test"),
               percent(o, "nrmse_cv") + " ± " + number(field(o, "nrmse_cv_sd"), "{:.2f}"), r(o, "r_train"),
               r(o, "r_test"), r(o, "r_cv"), r(o, "q2_cv"), verdict(o)});
  std::string body = paragraph(fmt::format("{} training rows, {} test rows ({}); cross-validation: {} folds over {} rows.",
                                           report.value("n_train", 0), report.value("n_test", 0),
                                           report.value("split", std::string()), report.value("cv_folds", 0),
                                           report.value("cv_rows", 0)));
  body += "<div class=\"scroll\">" + table.str() + "</div>\n";
  for (const auto &note : member(report, "notes"))
    if (note.is_string()) body += paragraph(note.get<std::string>());
  return body;
}
}  // namespace

PageSection surrogates_section(const fs::path &run) {
  if (!fs::is_directory(run / "train")) return {"surrogates", "Surrogates", ""};
  std::string body = paragraph(fmt::format(
      "NRMSE is the root-mean-square error over the range of the true values. The cross-validated figures are "
      "the error to expect on a new case; a map is trusted when its cross-validated Q² (the share of the variance "
      "of unseen cases it predicts) is at least {:.1f}.",
      analysis::min_trusted_q2_cv));
  for (const auto &entry : fs::directory_iterator(run / "train")) {
    if (!entry.is_directory()) continue;
    const std::string name = entry.path().filename().string();
    body += "<h3>" + html::escape(name) + "</h3>\n" + model_scores(entry.path());
    body += figure(entry.path() / "parity.png",
                   "Predicted against simulated: the training fit, test rows and the out-of-fold (cross-validated) "
                   "predictions of " + name + ".", "half");
  }
  return {"surrogates", "Surrogates and their accuracy", body};
}

PageSection map_section(const fs::path &run) {
  std::string body;
  for (const char *m : {spread_rate_column, roughness_column})
    body += figure(run / "map" / (std::string("surface_") + m + ".png"),
                   "The surrogate's " + metric_label(m) + " over (U, omega), with the simulated cases.", "half");
  if (body.empty()) return {"map", "Response surfaces", ""};
  return {"map", "Response surfaces", "<div class=\"figures\">" + body + "</div>\n"};
}

PageSection verify_section(const fs::path &run) {
  const json v = read_json(run / "map" / "verified.json");
  if (!v.is_object()) return {"verify", "Verification", ""};
  std::string body = v.value("verified", false)
                         ? paragraph("Verified: the simulations at the proposed optimum fall inside the predicted "
                                     "intervals.")
                         : warning("NOT verified: a simulation at the proposed optimum falls outside its predicted "
                                   "interval.");
  body += "<pre>" + html::escape(member(v, "points").dump(2)) + "</pre>\n";
  return {"verify", "Verification by simulation", body};
}

}  // namespace spreadmap::report
