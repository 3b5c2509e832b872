// The catalogue of malformed inputs: every file in tests/workflow/data/bad/ goes through the real
// binary (`spreadmap validate FILE`, or the command the file names) and must give the expected exit
// code (never a signal), name the file, the key path and, where the input has one, line:column
// (1-based), and say what is wrong. A file states its expectations in its leading comments:
//   # expect-exit: 2                  exit code
//   # expect-key: scene.powder.count  key path in the message
//   # expect-at: 11:20                position: the message holds "FILE:11:20: KEY"
//   # expect-file: scenes/x.yaml      the file the message names, when not the workflow itself
//   # expect-text: ...                further text of the message (any number of lines)
//   # expect-errors: 1                exact number of "error:" messages (e.g. reported once)
//   # with-env: NAME=VALUE            environment of the run (@FIXTURES@: the fixture plugins;
//                                     @ABI@ anywhere: the newest plugin ABI this host loads, "10.1")
//   # with-command: run @FILE@ --out @OUT@   instead of `validate @FILE@`
#include <gtest/gtest.h>
#include <spreadmap/abi.h>

#include <unistd.h>

#include <algorithm>
#include <fstream>
#include <regex>
#include <sstream>

#include "workflow/process.hpp"

namespace fs = std::filesystem;
namespace t = spreadmap::test;

namespace {

const fs::path catalogue_dir = fs::path(SPREADMAP_SOURCE_DIR) / "tests" / "workflow" / "data" / "bad";

struct Entry {
  fs::path file;
  int exit_code = -1;
  std::string key, at, names;
  std::vector<std::string> texts, command;
  std::map<std::string, std::string> env;
  int errors = -1;
};

std::string substitute(std::string s, const std::string &from, const std::string &to) {
  for (std::size_t p = s.find(from); p != std::string::npos; p = s.find(from, p + to.size()))
    s.replace(p, from.size(), to);
  return s;
}

std::string fixtures(std::string s) {
  s = substitute(std::move(s), "@ABI@",
                 std::to_string(SPREADMAP_PLUGIN_ABI_MAJOR) + "." + std::to_string(SPREADMAP_PLUGIN_ABI_MINOR));
  return substitute(std::move(s), "@FIXTURES@", SPREADMAP_FIXTURE_DIR);
}

Entry read_entry(const fs::path &file) {
  Entry e;
  e.file = file;
  std::ifstream in(file);
  const std::regex directive(
      R"(^# (expect-exit|expect-key|expect-at|expect-file|expect-text|expect-errors|with-env|with-command): (.*)$)");
  for (std::string line; std::getline(in, line) && line.rfind('#', 0) == 0;) {
    std::smatch m;
    if (!std::regex_match(line, m, directive)) continue;
    const std::string what = m[1], value = fixtures(m[2]);
    if (what == "expect-exit") e.exit_code = std::stoi(value);
    else if (what == "expect-key") e.key = value;
    else if (what == "expect-at") e.at = value;
    else if (what == "expect-file") e.names = value;
    else if (what == "expect-text") e.texts.push_back(value);
    else if (what == "expect-errors") e.errors = std::stoi(value);
    else if (what == "with-env") e.env[value.substr(0, value.find('='))] = value.substr(value.find('=') + 1);
    else if (what == "with-command") {
      std::istringstream words(value);
      for (std::string w; words >> w;) e.command.push_back(w);
    }
  }
  return e;
}

std::vector<Entry> catalogue() {
  std::vector<Entry> out;
  for (const auto &f : fs::directory_iterator(catalogue_dir))
    if (f.path().extension() == ".yaml") out.push_back(read_entry(f.path()));
  std::sort(out.begin(), out.end(), [](const Entry &a, const Entry &b) { return a.file < b.file; });
  return out;
}

std::size_t count_errors(const std::string &err) {
  std::size_t n = 0;
  std::istringstream in(err);
  for (std::string line; std::getline(in, line);) n += line.rfind("error: ", 0) == 0;
  return n;
}

// Files left half-written: temporary names of write_atomic ("*.tmp*") anywhere below `dir`.
std::vector<std::string> temporaries(const fs::path &dir) {
  std::vector<std::string> out;
  if (!fs::exists(dir)) return out;
  for (const auto &e : fs::recursive_directory_iterator(dir))
    if (e.path().filename().string().find(".tmp") != std::string::npos) out.push_back(e.path().string());
  return out;
}

void PrintTo(const Entry &e, std::ostream *os) { *os << e.file.filename(); }

class Catalogue : public ::testing::TestWithParam<Entry> {};

}  // namespace

TEST(CatalogueSize, AtLeastTwentyFiveMalformedInputs) { EXPECT_GE(catalogue().size(), 25u); }

TEST(CatalogueSize, EveryEntryStatesItsExpectations) {
  for (const auto &e : catalogue()) {
    EXPECT_GT(e.exit_code, 0) << e.file << ": no expect-exit";
    EXPECT_FALSE(e.texts.empty() && e.key.empty()) << e.file << ": nothing to expect";
  }
}

TEST_P(Catalogue, IsRejectedWithAClearMessage) {
  const Entry &e = GetParam();
  const fs::path out =
      fs::temp_directory_path() / ("spreadmap_catalogue_" + std::to_string(::getpid()) + "_" + e.file.stem().string());
  fs::remove_all(out);
  t::Command cmd;
  cmd.env = e.env;
  if (e.command.empty()) cmd.args = {"validate", e.file.string()};
  for (const auto &w : e.command)
    cmd.args.push_back(substitute(substitute(w, "@FILE@", e.file.string()), "@OUT@", out.string()));

  const t::Outcome r = t::run(cmd);
  ASSERT_TRUE(r.exited) << "crashed: " << r.describe();
  EXPECT_EQ(r.exit_code, e.exit_code) << r.describe();
  EXPECT_EQ(t::crash_marker(r.err), "") << r.describe();
  EXPECT_GE(count_errors(r.err), 1u) << "no line starts with 'error: '\n" << r.describe();

  const std::string named = (e.names.empty() ? e.file : e.file.parent_path() / e.names).string();
  if (!e.at.empty()) {
    EXPECT_NE(r.err.find(named + ":" + e.at + ": " + e.key), std::string::npos)
        << "expected '" << named << ":" << e.at << ": " << e.key << "' in\n"
        << r.err;
  } else {
    EXPECT_NE(r.err.find(named), std::string::npos) << "the message does not name " << named << ":\n" << r.err;
    EXPECT_NE(r.err.find(e.key), std::string::npos) << "the message does not name " << e.key << ":\n" << r.err;
  }
  for (const auto &text : e.texts)
    EXPECT_NE(r.err.find(text), std::string::npos) << "missing '" << text << "' in\n" << r.err;
  if (e.errors >= 0) {
    EXPECT_EQ(count_errors(r.err), std::size_t(e.errors)) << r.err;
  }
  EXPECT_EQ(temporaries(out), std::vector<std::string>{});
  if (!e.command.empty() && e.command.front() == "run") {
    EXPECT_FALSE(fs::exists(out)) << "an invalid workflow must be refused before the run directory is made";
  }
  fs::remove_all(out);
}

INSTANTIATE_TEST_SUITE_P(Bad, Catalogue, ::testing::ValuesIn(catalogue()),
                         [](const ::testing::TestParamInfo<Entry> &info) { return info.param.file.stem().string(); });
