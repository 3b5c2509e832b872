// The user guide kept true (README.md and docs/*.md), through the real binary:
// - every ```yaml block that is a complete file (its first key is `version:`) passes `spreadmap validate`:
//   it is written where its paths resolve as written, at the project's root, or where a first-line
//   comment naming a file puts it (`# examples/calibration/glass_beads.yaml`); other blocks are fragments;
// - every `spreadmap` command line in a ```sh, ```console or ```bash block names a real command and only
//   options that command's --help lists;
// - every relative link reaches a file, and the heading it names; every page is in docs/README.md;
// - the README fits on one page.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <fstream>
#include <iterator>
#include <map>
#include <set>
#include <sstream>

#include "workflow/process.hpp"

namespace fs = std::filesystem;
namespace t = spreadmap::test;

namespace {

const fs::path source = SPREADMAP_SOURCE_DIR;

std::string slurp(const fs::path &p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::vector<std::string> lines_of(const std::string &text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

bool starts_with(const std::string &s, const std::string &prefix) { return s.rfind(prefix, 0) == 0; }

std::string trim(const std::string &s) {
  const auto b = s.find_first_not_of(" \t\r");
  if (b == std::string::npos) return "";
  return s.substr(b, s.find_last_not_of(" \t\r") - b + 1);
}

// The guide's pages, relative to the project's root: README.md first, then docs/*.md by name.
std::vector<fs::path> pages() {
  std::vector<fs::path> docs;
  for (const auto &e : fs::directory_iterator(source / "docs"))
    if (e.is_regular_file() && e.path().extension() == ".md") docs.push_back(fs::relative(e.path(), source));
  std::sort(docs.begin(), docs.end());
  docs.insert(docs.begin(), fs::path("README.md"));
  return docs;
}

// A fenced code block of a page: its info string ("yaml", "sh", ...), the line of its opening fence
// (from 1) and its lines.
struct Block {
  std::string page;
  std::string language;
  std::size_t line = 0;
  std::vector<std::string> text;
  std::string where() const { return page + ":" + std::to_string(line); }
};

// A line that opens a fence (CommonMark): three or more backticks, then an info string without backticks.
bool opens_fence(const std::string &line, std::size_t &ticks, std::string &info) {
  ticks = 0;
  while (ticks < line.size() && line[ticks] == '`') ++ticks;
  if (ticks < 3 || line.find('`', ticks) != std::string::npos) return false;
  info = trim(line.substr(ticks));
  return true;
}

bool closes_fence(const std::string &line, std::size_t ticks) {
  std::size_t n = 0;
  while (n < line.size() && line[n] == '`') ++n;
  return n >= ticks && trim(line.substr(n)).empty();
}

// The code blocks of a page, and its other lines (prose, headings; numbered from 1) for links and headings.
struct Page {
  std::vector<Block> blocks;
  std::vector<std::pair<std::size_t, std::string>> prose;
};

Page parse_page(const std::string &name, const std::string &text) {
  Page page;
  const auto lines = lines_of(text);
  for (std::size_t i = 0; i < lines.size(); ++i) {
    std::size_t ticks = 0;
    std::string info;
    if (!opens_fence(lines[i], ticks, info)) {
      page.prose.emplace_back(i + 1, lines[i]);
      continue;
    }
    Block b;
    b.page = name;
    b.language = info.substr(0, info.find_first_of(" \t{"));
    b.line = i + 1;
    for (++i; i < lines.size() && !closes_fence(lines[i], ticks); ++i) b.text.push_back(lines[i]);
    page.blocks.push_back(b);
  }
  return page;
}

Page read_page(const fs::path &relative) { return parse_page(relative.string(), slurp(source / relative)); }

// ---- YAML blocks ------------------------------------------------------------------------------------

// A complete file: its first line that is neither blank nor a comment is `version: ...`.
bool is_complete_file(const Block &b) {
  for (const auto &line : b.text) {
    const std::string s = trim(line);
    if (s.empty() || s[0] == '#') continue;
    return starts_with(line, "version:");
  }
  return false;
}

// Where a complete block is validated, relative to the project's root: the file its first line names
// (`# examples/calibration/glass_beads.yaml, ...`), else a file of its own at the root.
fs::path block_location(const Block &b) {
  if (!b.text.empty() && starts_with(b.text[0], "# ")) {
    std::istringstream words(b.text[0].substr(2));
    std::string first;
    words >> first;
    while (!first.empty() && (first.back() == ',' || first.back() == ':' || first.back() == ';')) first.pop_back();
    const fs::path p = first;
    const bool inside = std::none_of(p.begin(), p.end(), [](const fs::path &c) { return c == ".."; });
    if (p.extension() == ".yaml" && p.is_relative() && inside && p.has_parent_path()) return p;
  }
  std::string stem = fs::path(b.page).stem().string();
  std::replace_if(
      stem.begin(), stem.end(), [](char c) { return !std::isalnum(static_cast<unsigned char>(c)); }, '_');
  return "guide_" + stem + "_" + std::to_string(b.line) + ".yaml";
}

// `dst` mirrors the folder `src`: every entry is a link to the original, except the first component of
// `rel`, which is a real folder mirroring the rest of `rel` in turn (its last component, the file, is
// left out). A file written at dst / rel then sees the project around it as the original would.
void mirror(const fs::path &src, const fs::path &dst, const fs::path &rel) {
  fs::create_directories(dst);
  const fs::path first = *rel.begin();
  if (fs::is_directory(src))
    for (const auto &e : fs::directory_iterator(src))
      if (e.path().filename() != first) fs::create_symlink(e.path(), dst / e.path().filename());
  fs::path rest;
  for (auto it = std::next(rel.begin()); it != rel.end(); ++it) rest /= *it;
  if (!rest.empty()) mirror(src / first, dst / first, rest);
}

fs::path fresh_dir() {
  static int counter = 0;
  const fs::path d =
      fs::temp_directory_path() / ("spreadmap_guide_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
  fs::remove_all(d);
  return d;
}

// Validates a complete block where it belongs; "" when `spreadmap validate` accepts it, else why not.
std::string validate_block(const Block &b) {
  const fs::path dir = fresh_dir(), rel = block_location(b);
  mirror(source, dir, rel);
  const fs::path file = dir / rel;
  {
    std::ofstream out(file);
    for (const auto &line : b.text) out << line << "\n";
  }
  const t::Outcome r = t::run({{"validate", file.string()}, {}, {}, dir});
  std::string problem;
  if (!r.exited || r.exit_code != 0 || r.out.find(file.string() + ": ok (") == std::string::npos)
    problem = b.where() + ": this complete file (validated as " + rel.string() +
              ") is refused by spreadmap validate: " + r.describe();
  fs::remove_all(dir);
  return problem;
}

// ---- Command lines ----------------------------------------------------------------------------------

// What `spreadmap COMMAND --help` says, once per command.
struct Help {
  bool exists = false;
  std::set<std::string> options;  // "--jobs", "-j", ...
  std::string text;
};

Help help_of(const std::string &command) {
  static std::map<std::string, Help> known;
  if (auto it = known.find(command); it != known.end()) return it->second;
  Help h;
  const t::Outcome r = t::run({{command, "--help"}, {}, {}, {}});
  h.text = r.describe();
  h.exists = r.exited && r.exit_code == 0 && r.out.find("usage: spreadmap " + command) != std::string::npos;
  const std::string &s = r.out;
  for (std::size_t i = 0; i + 1 < s.size(); ++i) {
    if (s[i] != '-' || (i > 0 && !std::isspace(static_cast<unsigned char>(s[i - 1])) && s[i - 1] != '[')) continue;
    std::size_t j = i + 1;
    if (s[j] == '-') ++j;
    const std::size_t from = j;
    while (j < s.size() && (std::isalnum(static_cast<unsigned char>(s[j])) || s[j] == '-' || s[j] == '_')) ++j;
    if (j == from) continue;
    const std::string option = s.substr(i, j - i);
    if (option[1] == '-' || option.size() == 2) h.options.insert(option);  // --long, or -x alone
    i = j - 1;
  }
  known[command] = h;
  return h;
}

// The words of a shell line, its comment left out (a '#' that starts a word).
std::vector<std::string> words_of(const std::string &line) {
  std::vector<std::string> words;
  std::istringstream in(line);
  for (std::string w; in >> w;) {
    if (w[0] == '#') break;
    words.push_back(w);
  }
  return words;
}

bool is_program(const std::string &word) { return word == "spreadmap" || word.ends_with("/spreadmap"); }

// The word that names the program in a shell line: the first word, or the first after a launcher
// (`mpirun -n 4 build/bin/spreadmap ...`) or after variables set for it (`OMP_NUM_THREADS=2 spreadmap ...`).
std::vector<std::string>::const_iterator program_word(const std::vector<std::string> &words) {
  static const std::set<std::string> launchers = {"mpirun", "mpiexec", "srun", "time", "nice", "env", "sudo"};
  auto w = words.begin();
  while (w != words.end() && w->find('=') != std::string::npos && (*w)[0] != '-') ++w;
  if (w == words.end()) return w;
  if (is_program(*w)) return w;
  if (!launchers.count(*w)) return words.end();
  return std::find_if(std::next(w), words.end(), is_program);
}

bool is_shell_operator(const std::string &w) {
  static const std::set<std::string> ops = {"|", "||", "&&", ";", "&", ">", ">>", "<", "2>", "2>&1", "&>"};
  return ops.count(w) > 0;
}

struct CommandLine {
  std::string where;
  std::vector<std::string> args;  // after the program
};

// The spreadmap command lines of a shell block: continuation lines joined, a console's "$ " prompt
// dropped, from the word naming the program (`spreadmap`, `build/bin/spreadmap`) to a shell operator.
std::vector<CommandLine> command_lines(const Block &b) {
  std::vector<CommandLine> found;
  std::string joined;
  std::size_t first = 0;
  for (std::size_t k = 0; k < b.text.size(); ++k) {
    std::string line = b.text[k];
    if (joined.empty()) first = k;
    if (!line.empty() && line.back() == '\\') {
      joined += line.substr(0, line.size() - 1) + " ";
      continue;
    }
    joined += line;
    std::string s = trim(joined);
    joined.clear();
    if (b.language == "console") {
      if (!starts_with(s, "$ ")) continue;  // output, not a command
      s = s.substr(2);
    }
    const auto words = words_of(s);
    const auto program = program_word(words);
    if (program == words.end()) continue;
    CommandLine c;
    c.where = b.page + ":" + std::to_string(b.line + 1 + first);
    for (auto w = std::next(program); w != words.end() && !is_shell_operator(*w); ++w) c.args.push_back(*w);
    found.push_back(c);
  }
  return found;
}

// What is wrong with one command line: "" when its command exists and its --help lists every option.
std::string check_command(const CommandLine &c) {
  if (c.args.empty()) return c.where + ": spreadmap without a command";
  const std::string &command = c.args[0];
  if (starts_with(command, "-")) {
    static const std::set<std::string> top = {"--help", "-h", "--version"};
    return top.count(command) ? std::string()
                              : c.where + ": spreadmap " + command + ": not an option of spreadmap itself";
  }
  const Help h = help_of(command);
  if (!h.exists)
    return c.where + ": spreadmap " + command + ": not a command (spreadmap " + command + " --help: " + h.text + ")";
  std::string problems;
  for (std::size_t i = 1; i < c.args.size(); ++i) {
    std::string w = c.args[i];
    while (!w.empty() && w.front() == '[') w.erase(w.begin());  // [--jobs N]: an optional part of a synopsis
    while (!w.empty() && (w.back() == ']' || w.back() == ',')) w.pop_back();
    if (w.size() < 2 || w[0] != '-') continue;
    if (!std::isalpha(static_cast<unsigned char>(w[1])) && w[1] != '-') continue;  // a negative number
    const std::string option = w.substr(0, w.find('='));
    if (!h.options.count(option))
      problems +=
          c.where + ": spreadmap " + command + " has no option " + option + " (see spreadmap " + command + " --help)\n";
  }
  return problems;
}

bool is_shell(const Block &b) { return b.language == "sh" || b.language == "console" || b.language == "bash"; }

// ---- Links and headings -----------------------------------------------------------------------------

// A line with its inline code spans (`...`, ``...``) blanked out: links inside them are not links.
std::string without_code_spans(const std::string &line) {
  std::string out;
  for (std::size_t i = 0; i < line.size();) {
    if (line[i] != '`') {
      out += line[i++];
      continue;
    }
    std::size_t n = 0;
    while (i + n < line.size() && line[i + n] == '`') ++n;
    const std::string run(n, '`');
    std::size_t close = line.find(run, i + n);
    while (close != std::string::npos && close + n < line.size() && line[close + n] == '`')
      close = line.find(run, close + n + 1);
    if (close == std::string::npos) {
      out += run;
      i += n;
      continue;
    }
    out += ' ';
    i = close + n;
  }
  return out;
}

// A heading's anchor as GitHub makes it: lower case, punctuation dropped, spaces turned into '-'.
std::string anchor_of(const std::string &heading) {
  std::string out;
  for (std::size_t i = 0; i < heading.size(); ++i) {
    const auto c = static_cast<unsigned char>(heading[i]);
    if (c >= 0x80) {
      // en and em dashes are punctuation; other non-ASCII characters (letters, symbols) stay
      if (heading.compare(i, 3, "\xE2\x80\x93") == 0 || heading.compare(i, 3, "\xE2\x80\x94") == 0) {
        i += 2;
        continue;
      }
      out += static_cast<char>(c);
    } else if (std::isalnum(c) || c == '-' || c == '_') {
      out += static_cast<char>(std::tolower(c));
    } else if (c == ' ') {
      out += '-';
    }
  }
  return out;
}

std::set<std::string> anchors_of(const Page &page) {
  std::set<std::string> anchors;
  for (const auto &numbered : page.prose) {
    const std::string &line = numbered.second;
    if (!starts_with(line, "#")) continue;
    const auto text = line.find_first_not_of('#');
    if (text == std::string::npos || line[text] != ' ') continue;
    anchors.insert(anchor_of(trim(line.substr(text))));
  }
  return anchors;
}

struct Link {
  std::size_t line;
  std::string target;
};

std::vector<Link> links_of(const Page &page) {
  std::vector<Link> links;
  for (const auto &[n, raw] : page.prose) {
    const std::string line = without_code_spans(raw);  // links in code are not links
    for (std::size_t at = line.find("]("); at != std::string::npos; at = line.find("](", at + 2)) {
      const std::size_t end = line.find(')', at + 2);
      if (end == std::string::npos) break;
      std::string target = line.substr(at + 2, end - at - 2);
      target = target.substr(0, target.find(' '));  // [text](target "title")
      links.push_back({n, target});
    }
  }
  return links;
}

// What is wrong with the relative links of a page: a file that is not there, a heading it does not have.
std::string check_links(const fs::path &relative, const Page &page) {
  std::string problems;
  for (const auto &l : links_of(page)) {
    const std::string where = relative.string() + ":" + std::to_string(l.line) + ": link " + l.target;
    if (l.target.empty() || l.target.find("://") != std::string::npos || starts_with(l.target, "mailto:")) continue;
    const auto hash = l.target.find('#');
    const std::string file = l.target.substr(0, hash);
    const std::string anchor = hash == std::string::npos ? std::string() : l.target.substr(hash + 1);
    const fs::path target = file.empty() ? source / relative : (source / relative).parent_path() / file;
    if (!fs::exists(target)) {
      problems += where + ": no such file " + fs::relative(target.lexically_normal(), source).string() + "\n";
      continue;
    }
    if (anchor.empty() || target.extension() != ".md") continue;
    const Page linked = file.empty() ? page : parse_page(target.string(), slurp(target));
    if (!anchors_of(linked).count(anchor)) problems += where + ": no heading with the anchor #" + anchor + "\n";
  }
  return problems;
}

}  // namespace

TEST(GuideExamples, EveryCompleteYamlBlockValidates) {
  std::size_t complete = 0, in_readme = 0;
  for (const auto &p : pages()) {
    const Page page = read_page(p);
    for (const auto &b : page.blocks) {
      if (b.language != "yaml" || !is_complete_file(b)) continue;
      ++complete;
      if (b.page == "README.md") ++in_readme;
      SCOPED_TRACE(b.where());
      EXPECT_EQ(validate_block(b), "");
    }
  }
  EXPECT_GE(in_readme, 1u) << "the README shows no complete workflow";
  EXPECT_GE(complete, 3u) << "fewer complete YAML files in the guide than it had when this test was written";
}

TEST(GuideExamples, EveryCommandLineNamesARealCommandAndItsOptions) {
  std::size_t checked = 0;
  for (const auto &p : pages()) {
    const Page page = read_page(p);
    for (const auto &b : page.blocks) {
      if (!is_shell(b)) continue;
      for (const auto &c : command_lines(b)) {
        ++checked;
        EXPECT_EQ(check_command(c), "");
      }
    }
  }
  EXPECT_GE(checked, 10u) << "fewer spreadmap command lines in the guide than it had when this test was written";
}

TEST(GuideExamples, EveryRelativeLinkReachesAFileAndItsHeading) {
  for (const auto &p : pages()) EXPECT_EQ(check_links(p, read_page(p)), "");
}

TEST(GuideExamples, EveryPageIsInTheIndex) {
  std::set<std::string> indexed;
  for (const auto &l : links_of(read_page("docs/README.md"))) indexed.insert(l.target.substr(0, l.target.find('#')));
  for (const auto &p : pages()) {
    if (p == "README.md" || p == "docs/README.md") continue;
    EXPECT_EQ(indexed.count(p.filename().string()), 1u) << p << " is not linked from docs/README.md";
  }
  std::set<std::string> from_readme;
  for (const auto &l : links_of(read_page("README.md"))) from_readme.insert(l.target);
  EXPECT_EQ(from_readme.count("docs/README.md"), 1u) << "the README does not link the guide's index";
}

TEST(GuideExamples, TheReadmeFitsOnePage) {
  EXPECT_LE(lines_of(slurp(source / "README.md")).size(), 150u)
      << "README.md is the one-page introduction: move the detail into a page of docs/";
}

// The checks above must be able to fail: a broken workflow, an unknown option and a dead link in a
// page made up here are each caught.
TEST(GuideExamples, ABrokenExampleIsCaught) {
  const std::string text =
      "# A page\n\n"
      "```yaml\n"
      "version: 1\n"
      "name: broken\n"
      "scene:\n"
      "  preset: quikc\n"
      "stages:\n"
      "  - simulate:\n"
      "      design: {type: list, cases: [{U: 100 mm/s}]}\n"
      "```\n\n"
      "```yaml\n"
      "  - map: {model: gp}\n"
      "```\n\n"
      "```sh\n"
      "build/bin/spreadmap run workflows/quickstart.yaml --jbos 2   # a typo\n"
      "spreadmap valdate workflows/quickstart.yaml\n"
      "```\n\n"
      "See [the map](workflows.md#no-such-heading) and [a page](no-such-page.md).\n";
  const Page page = parse_page("docs/broken.md", text);
  ASSERT_EQ(page.blocks.size(), 3u);
  EXPECT_TRUE(is_complete_file(page.blocks[0]));
  EXPECT_FALSE(is_complete_file(page.blocks[1])) << "a fragment is not a file";
  EXPECT_NE(validate_block(page.blocks[0]).find("preset"), std::string::npos) << validate_block(page.blocks[0]);

  const auto commands = command_lines(page.blocks[2]);
  ASSERT_EQ(commands.size(), 2u);
  EXPECT_NE(check_command(commands[0]).find("no option --jbos"), std::string::npos) << check_command(commands[0]);
  EXPECT_NE(check_command(commands[1]).find("not a command"), std::string::npos) << check_command(commands[1]);

  const std::string links = check_links("docs/broken.md", page);
  EXPECT_NE(links.find("no heading with the anchor #no-such-heading"), std::string::npos) << links;
  EXPECT_NE(links.find("no such file docs/no-such-page.md"), std::string::npos) << links;
}
