#include "workflow/report/run_report.hpp"

#include <algorithm>
#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "core/files.hpp"
#include "workflow/report/html.hpp"
#include "workflow/report/report_sections.hpp"
#include "workflow/report/report_style.hpp"
#include "workflow/run/run_dir.hpp"

namespace spreadmap {

fs::path write_run_report(const fs::path &run) {
  using nlohmann::json;
  const json manifest = report::read_json(run / "manifest.json");
  if (!manifest.is_object())
    throw InputError("report: " + run.string() +
                     " holds no readable manifest.json: give the run directory a workflow wrote, e.g. runs/quickstart");
  const std::string name = report::member(manifest, "workflow").value("name", run.filename().string());
  const std::vector<report::PageSection> sections = {
      report::answer_section(run),   report::scene_section(manifest),  report::cases_section(run, manifest),
      report::surrogates_section(run), report::map_section(run),        report::verify_section(run),
      report::provenance_section(run, manifest)};
  // the stages in the order they ran (their ISO start times sort so)
  std::vector<std::pair<std::string, std::string>> ran;
  for (const auto &[k, v] : report::member(manifest, "stages").items()) ran.emplace_back(v.value("start", ""), k);
  std::sort(ran.begin(), ran.end());
  std::string stages;
  for (const auto &r : ran) stages += (stages.empty() ? "" : ", ") + r.second;
  std::string page = report::page_head("spreadmap: " + name);
  page += "<header>\n<h1>" + html::escape(name) + "</h1>\n";
  page += report::paragraph("spreadmap run report, written " + RunDirectory::now_iso() +
                            (stages.empty() ? "; no stage has finished yet." : "; stages finished: " + stages + "."));
  page += "<nav>";
  for (const auto &s : sections)
    if (!s.body.empty()) page += "<a href=\"#" + s.id + "\">" + html::escape(s.title) + "</a> ";
  page += "</nav>\n</header>\n<main>\n";
  for (const auto &s : sections)
    if (!s.body.empty())
      page += "<section id=\"" + s.id + "\">\n<h2>" + html::escape(s.title) + "</h2>\n" + s.body + "</section>\n";
  page += "</main>\n</body>\n</html>\n";
  const fs::path out = run / "report.html";
  write_atomic(out, page);
  return out;
}

}  // namespace spreadmap
