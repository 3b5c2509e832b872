// The quickstart's report.html: one self-contained page (every image inline, nothing to fetch), a
// well-formed document, rebuilt by `spreadmap report`, and read in a real browser (headless
// Chromium): every image decodes, no error reaches the console, and neither the 1280 px screen
// layout nor the A4 print layout is wider than its page.
#include <regex>
#include <sstream>

#include "integration/quickstart_run.hpp"

namespace {

using namespace quickstart;

std::string text_of(const fs::path &p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::size_t count(const std::string &text, const std::string &what) {
  std::size_t n = 0;
  for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + what.size())) ++n;
  return n;
}

// The page with a probe in its <head>: it records script errors and failed loads, and on load writes
// "CHECK images=N broken=N errors=N overflow=0|1" into the page, for --dump-dom to read back.
std::string probed(std::string page) {
  const std::string probe = R"(<script>
window.__errors = [];
window.addEventListener('error', function (e) { window.__errors.push(String(e.message || e.type)); }, true);
var __log = console.error; console.error = function () { window.__errors.push('console'); __log.apply(console, arguments); };
window.addEventListener('load', function () {
  var imgs = Array.prototype.slice.call(document.images);
  var broken = imgs.filter(function (i) { return !(i.complete && i.naturalWidth > 0); }).length;
  var over = document.documentElement.scrollWidth > window.innerWidth + 1 ? 1 : 0;
  var out = document.createElement('pre');
  out.textContent = 'CHECK images=' + imgs.length + ' broken=' + broken + ' errors=' + window.__errors.length +
                    ' overflow=' + over + ' width=' + window.innerWidth;
  document.body.appendChild(out);
});
</script>)";
  page.insert(page.find("<head>") + 6, probe);
  return page;
}

struct BrowserCheck {
  int images = -1, broken = -1, errors = -1, overflow = -1, width = -1;
  std::string dom;
};

BrowserCheck open_in_chromium(const fs::path &html, int width) {
  BrowserCheck c;
  shell("chromium --headless --no-sandbox --disable-gpu --hide-scrollbars --window-size=" + std::to_string(width) +
            ",1000 --virtual-time-budget=10000 --dump-dom file://" + html.string(),
        &c.dom);
  std::smatch m;
  if (std::regex_search(c.dom, m,
                        std::regex("CHECK images=(\\d+) broken=(\\d+) errors=(\\d+) overflow=(\\d) width=(\\d+)")))
    c.images = std::stoi(m[1]), c.broken = std::stoi(m[2]), c.errors = std::stoi(m[3]), c.overflow = std::stoi(m[4]),
    c.width = std::stoi(m[5]);
  return c;
}

const fs::path report = run_dir / "report.html";

}  // namespace

TEST_F(Quickstart, ReportIsOneSelfContainedWellFormedPage) {
  ASSERT_EQ(status_, 0) << log_;
  ASSERT_TRUE(fs::exists(report));
  const std::string page = text_of(report);
  // every stage's part: the answer, the scene, the nine cases, both surrogates, the map, the provenance
  for (const char *id : {"answer", "scene", "cases", "surrogates", "map", "provenance"})
    EXPECT_NE(page.find("<section id=\"" + std::string(id) + "\">"), std::string::npos) << id;
  // images: 9 snapshots, the map, 2 parity plots, 2 surfaces, all inline
  EXPECT_EQ(count(page, "<img "), 14u);
  EXPECT_EQ(count(page, "src=\"data:image/png;base64,"), 14u);
  // nothing to fetch: every src and href is inline data or a link within the page
  // (scanned by hand: std::regex recurses once per character of a megabyte-long data URI)
  for (const std::string attribute : {" src=\"", " href=\""})
    for (auto at = page.find(attribute); at != std::string::npos; at = page.find(attribute, at + 1)) {
      const std::string target = page.substr(at + attribute.size(), 16);
      EXPECT_TRUE(target.rfind("data:", 0) == 0 || target.rfind("#", 0) == 0) << "external reference: " << target;
    }
  // a strict parser: the page is well-formed (every element closed, every entity valid)
  std::string out;
  EXPECT_EQ(shell("xmllint --noout " + report.string(), &out), 0) << out;
}

TEST_F(Quickstart, ReportCommandRebuildsTheSamePage) {
  ASSERT_EQ(status_, 0) << log_;
  const RunLock lock;
  const std::string before = text_of(report);
  std::string out;
  ASSERT_EQ(run("report " + run_dir.string(), &out), 0) << out;
  const std::string after = text_of(report);
  // the same page but for the line that says when it was written
  const std::regex when("written [0-9T:\\-]+Z");
  EXPECT_EQ(std::regex_replace(before, when, ""), std::regex_replace(after, when, ""));
  EXPECT_NE(run("report " + (run_dir / "cases").string(), &out), 0) << "a folder that is no run directory is refused";
  EXPECT_NE(out.find("manifest.json"), std::string::npos) << out;
}

TEST_F(Quickstart, ReportReadsInAHeadlessBrowserOnScreenAndOnA4) {
  ASSERT_EQ(status_, 0) << log_;
  const fs::path dir = fs::path(SPREADMAP_BINARY_DIR) / "test-runs" / "report-browser";
  fs::create_directories(dir);
  const std::string page = text_of(report);
  {
    std::ofstream(dir / "screen.html") << probed(page);
    // print rules applied on screen, at the width of an A4 page inside 14 mm margins (182 mm at 96 px/in)
    std::string print = probed(page);
    print = std::regex_replace(print, std::regex("@media print"), "@media all");
    std::ofstream(dir / "print.html") << print;
  }
  const BrowserCheck screen = open_in_chromium(dir / "screen.html", 1280);
  ASSERT_EQ(screen.images, 14) << "the probe did not report; the browser said:\n" << screen.dom.substr(0, 2000);
  EXPECT_EQ(screen.broken, 0) << "an image did not decode";
  EXPECT_EQ(screen.errors, 0) << "errors reached the console";
  EXPECT_EQ(screen.overflow, 0) << "wider than a 1280 px window";
  const BrowserCheck a4 = open_in_chromium(dir / "print.html", 688);
  EXPECT_EQ(a4.broken, 0);
  EXPECT_EQ(a4.errors, 0);
  EXPECT_EQ(a4.overflow, 0) << "wider than an A4 page";
  // and Chromium prints it to a PDF
  std::string out;
  fs::remove(dir / "report.pdf");
  shell("chromium --headless --no-sandbox --disable-gpu --no-pdf-header-footer --print-to-pdf=" +
            (dir / "report.pdf").string() + " file://" + report.string(),
        &out);
  ASSERT_TRUE(fs::exists(dir / "report.pdf")) << out;
  EXPECT_EQ(text_of(dir / "report.pdf").substr(0, 5), "%PDF-");
}
