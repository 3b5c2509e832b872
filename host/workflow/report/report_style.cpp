#include "workflow/report/report_style.hpp"

#include "workflow/report/html.hpp"

namespace spreadmap::report {

namespace {
// Screen: one column at most 1180 px wide, tables that scroll inside their box rather than widen the
// page. Print (A4): the same column at the page's width, each figure and table kept on one page.
constexpr const char *style = R"css(
:root { --ink: #1b1f24; --muted: #5a6470; --line: #d5dbe1; --warn: #a40000; --accent: #0b5cad; }
* { box-sizing: border-box; }
body { margin: 0; font: 15px/1.5 "DejaVu Sans", "Liberation Sans", Arial, sans-serif; color: var(--ink); background: #fff; }
header, main { max-width: 1180px; margin: 0 auto; padding: 0 24px; }
header { border-bottom: 2px solid var(--line); padding-top: 12px; padding-bottom: 8px; }
h1 { font-size: 26px; margin: 8px 0 4px; }
h2 { font-size: 20px; margin: 28px 0 8px; border-bottom: 1px solid var(--line); padding-bottom: 4px; }
h3 { font-size: 16px; margin: 18px 0 6px; }
nav a { color: var(--accent); margin-right: 14px; text-decoration: none; }
p { margin: 6px 0; max-width: 90ch; }
.warn { color: var(--warn); font-weight: bold; }
.scroll { overflow-x: auto; max-width: 100%; }
table { border-collapse: collapse; margin: 8px 0; font-size: 13px; }
th, td { border: 1px solid var(--line); padding: 3px 7px; text-align: left; vertical-align: middle; }
th { background: #eef2f6; }
td { overflow-wrap: anywhere; }
table.keys td:first-child { white-space: nowrap; color: var(--muted); }
figure { margin: 10px 0; }
figcaption { color: var(--muted); font-size: 13px; }
img { max-width: 100%; height: auto; }
img.wide { width: 100%; }
img.half { width: 100%; max-width: 560px; }
img.thumb { width: 150px; }
.figures { display: flex; flex-wrap: wrap; gap: 12px; }
.figures figure { flex: 1 1 420px; max-width: 560px; }
pre { background: #f6f8fa; border: 1px solid var(--line); padding: 8px; font-size: 12px; overflow-x: auto;
      white-space: pre-wrap; overflow-wrap: anywhere; }
details summary { cursor: pointer; color: var(--accent); }
@media print {
  @page { size: A4; margin: 14mm; }
  body { font-size: 10.5pt; }
  header, main { max-width: none; padding: 0; }
  nav { display: none; }
  details { display: block; }
  details > * { display: block; }
  section, figure, table { break-inside: avoid; }
  h2 { break-after: avoid; }
  img.thumb { width: 90px; }
  .scroll { overflow: visible; }
  table { font-size: 8.5pt; }
}
)css";
}  // namespace

std::string page_head(const std::string &title) {
  return "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\"/>\n"
         "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\"/>\n<title>" +
         html::escape(title) + "</title>\n<style>" + style + "</style>\n</head>\n<body>\n";
}

}  // namespace spreadmap::report
