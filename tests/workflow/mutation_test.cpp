// Every shipped workflow and example scene file, mutated leaf by leaf, through the real binary
// (`spreadmap validate`, one run over all mutants of a file): each scalar becomes a word, a NaN, 1e308 and a quantity
// of the wrong dimension, and each key gets a typo. Whatever the mutation, the program must answer as it does for any
// bad input — exit 0 (the mutation happens to be valid) or 2, never a signal, never a raw library message (a JSON or
// YAML exception, a sanitizer report) — and an error must name the file and the key it refuses. A typo in a stage's
// setting (stages[i].STAGE.KEY) is always refused, at its file:line, with the key it meant as the did-you-mean.
#include <gtest/gtest.h>
#include <unistd.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cctype>
#include <fstream>

#include "workflow/process.hpp"

namespace fs = std::filesystem;
namespace t = spreadmap::test;

namespace {

// A leaf's or key's place in the document: map keys and sequence indices from the root.
using Path = std::vector<std::string>;

std::string dotted(const Path &p) {
  std::string s;
  for (const auto &k : p) s += (s.empty() ? "" : ".") + k;
  return s;
}

void collect(const YAML::Node &n, Path &at, std::vector<Path> &leaves, std::vector<Path> &keys) {
  if (n.IsMap()) {
    for (const auto &kv : n) {
      at.push_back(kv.first.as<std::string>());
      keys.push_back(at);
      collect(kv.second, at, leaves, keys);
      at.pop_back();
    }
  } else if (n.IsSequence()) {
    for (std::size_t i = 0; i < n.size(); ++i) {
      at.push_back(std::to_string(i));
      collect(n[i], at, leaves, keys);
      at.pop_back();
    }
  } else if (n.IsScalar()) {
    leaves.push_back(at);
  }
}

// The node at `p` in a deep copy of `root` (yaml-cpp nodes share their data: Clone first).
YAML::Node at(YAML::Node root, const Path &p) {
  YAML::Node n = root;
  for (const auto &k : p) n.reset(n.IsSequence() ? n[std::stoul(k)] : n[k]);
  return n;
}

struct Mutant {
  std::string what;  // "scene.powder.count = abc"
  std::string key;   // the key the mutation touched: the message must name it
  YAML::Node doc;
  std::string meant = "";  // a stage setting's typo: the key the did-you-mean must offer
};

// The last map key of a path (a list entry is named by the key that holds the list).
std::string last_key(const Path &p) {
  for (auto it = p.rbegin(); it != p.rend(); ++it)
    if (!std::isdigit(static_cast<unsigned char>((*it)[0]))) return *it;
  return "";
}

std::vector<Mutant> mutants(const fs::path &workflow) {
  const YAML::Node original = YAML::LoadFile(workflow.string());
  std::vector<Path> leaves, keys;
  Path p;
  collect(original, p, leaves, keys);
  std::vector<Mutant> out;
  for (const auto &leaf : leaves)
    for (const char *value : {"abc", ".nan", "1e308", "3 kg"}) {
      YAML::Node doc = YAML::Clone(original);
      at(doc, leaf) = value;
      out.push_back({dotted(leaf) + " = " + value, last_key(leaf), doc});
    }
  for (const auto &key : keys) {
    if (std::isdigit(static_cast<unsigned char>(key.back()[0]))) continue;
    YAML::Node doc = YAML::Clone(original);
    Path parent(key.begin(), key.end() - 1);
    YAML::Node holder = parent.empty() ? doc : at(doc, parent);
    const YAML::Node value = YAML::Clone(holder[key.back()]);
    holder.remove(key.back());
    holder[key.back() + "x"] = value;
    const bool stage_setting = key.size() == 4 && key[0] == "stages";  // stages.N.STAGE.KEY
    out.push_back({dotted(key) + " renamed " + key.back() + "x", key.back() + "x", doc, stage_setting ? key.back() : ""});
  }
  return out;
}

// The shipped workflows and example scene files (`spreadmap validate` checks both kinds).
std::vector<fs::path> shipped_workflows() {
  std::vector<fs::path> files;
  for (const char *folder : {"workflows", "examples/scenes"})
    for (const auto &e : fs::directory_iterator(fs::path(SPREADMAP_SOURCE_DIR) / folder))
      if (e.path().extension() == ".yaml") files.push_back(e.path());
  std::sort(files.begin(), files.end());
  return files;
}

class Mutation : public ::testing::TestWithParam<fs::path> {};

// One mutant's answer, from a run of `spreadmap validate` on it alone or on many files at once.
struct Answer {
  bool refused = false;
  std::string message;  // what the program said of this file (refused ones)
};

// Checks one mutant's answer: a refusal names the file and the key.
void check_answer(const Mutant &m, const fs::path &file, const Answer &a, std::size_t &refused,
                  std::vector<std::string> &accepted) {
  SCOPED_TRACE(m.what);
  if (!m.meant.empty()) {
    EXPECT_TRUE(a.refused) << "a typo in a stage's settings was accepted";
    EXPECT_NE(a.message.find("did you mean '" + m.meant + "'"), std::string::npos) << a.message;
    const std::size_t at = a.message.find(file.string() + ":");
    EXPECT_TRUE(at != std::string::npos && std::isdigit(static_cast<unsigned char>(a.message[at + file.string().size() + 1])))
        << "no file:line:\n" << a.message;
  }
  if (!a.refused) {
    accepted.push_back(m.what);
    return;
  }
  ++refused;
  EXPECT_NE(a.message.find(file.string()), std::string::npos) << "the message does not name the file:\n" << a.message;
  EXPECT_NE(a.message.find(m.key), std::string::npos) << "the message does not name " << m.key << ":\n" << a.message;
}

// The mutants validated one process each: slow under the sanitizers, but it names the mutant that
// crashes. The fallback when the single run over all of them did not end cleanly.
void validate_one_by_one(const std::vector<Mutant> &all, const std::vector<fs::path> &files, std::size_t &refused,
                         std::vector<std::string> &accepted) {
  for (std::size_t i = 0; i < all.size(); ++i) {
    const t::Outcome r = t::run({{"validate", files[i].string()}, {}, {}, {}});
    SCOPED_TRACE(all[i].what);
    ASSERT_TRUE(r.exited) << "crashed: " << r.describe();
    EXPECT_EQ(t::crash_marker(r.err), "") << r.describe();
    EXPECT_TRUE(r.exit_code == 0 || r.exit_code == 2) << r.describe();
    check_answer(all[i], files[i], {r.exit_code != 0, r.err}, refused, accepted);
  }
}

}  // namespace

TEST_P(Mutation, EveryMutantGetsACleanAnswer) {
  const fs::path source = SPREADMAP_SOURCE_DIR,
                 dir = fs::temp_directory_path() / ("spreadmap_mutation_" + std::to_string(::getpid()));
  // The mutants sit where the original does relative to the project's root (workflows/, examples/scenes/),
  // beside copies of its folder's other files (particle CSVs); the project's other top folders are
  // linked in, so that a path such as ../examples/calibration/... resolves as it does for the original.
  const fs::path home = dir / fs::relative(GetParam().parent_path(), source);
  fs::create_directories(home);
  for (const char *top : {"examples", "workflows"})
    if (!fs::exists(dir / top)) fs::create_directory_symlink(source / top, dir / top);
  for (const auto &e : fs::directory_iterator(GetParam().parent_path()))
    if (e.is_regular_file() && e.path().extension() != ".yaml")
      fs::copy_file(e.path(), home / e.path().filename(), fs::copy_options::overwrite_existing);
  const std::vector<Mutant> all = mutants(GetParam());
  std::vector<fs::path> files;
  std::vector<std::string> args = {"validate"};
  for (std::size_t i = 0; i < all.size(); ++i) {
    char tag[32];  // ".m" and up to 20 digits
    std::snprintf(tag, sizeof tag, ".m%05zu", i);
    files.push_back(home / (GetParam().stem().string() + tag + ".yaml"));
    std::ofstream out(files.back());
    YAML::Emitter emit;
    emit << all[i].doc;
    out << emit.c_str() << "\n";
    args.push_back(files.back().string());
  }
  // All mutants in one process (validate takes many files and answers each): one start instead of
  // hundreds, which under AddressSanitizer is most of the time. Each valid file gets "FILE: ok" on
  // stdout; each refused one its message on stderr, in order, so a refused file's message runs
  // from its name to the next refused file's name.
  const t::Outcome r = t::run({args, {}, {}, {}});
  std::size_t refused = 0;
  std::vector<std::string> accepted;
  if (!r.exited || !t::crash_marker(r.err).empty() || (r.exit_code != 0 && r.exit_code != 2)) {
    ADD_FAILURE() << "validate over all " << all.size() << " mutants did not end cleanly (" << r.describe()
                  << "); validating them one by one to name the mutant";
    validate_one_by_one(all, files, refused, accepted);
  } else {
    std::vector<bool> ok(all.size());
    std::vector<std::size_t> starts;
    for (std::size_t i = 0; i < all.size(); ++i) {
      ok[i] = r.out.find(files[i].string() + ": ok (") != std::string::npos;
      if (!ok[i]) starts.push_back(std::min(r.err.size(), r.err.find(files[i].string())));
    }
    for (std::size_t i = 0, k = 0; i < all.size(); ++i) {
      if (ok[i]) {
        check_answer(all[i], files[i], {}, refused, accepted);
        continue;
      }
      const std::size_t from = starts[k], to = k + 1 < starts.size() ? starts[k + 1] : r.err.size();
      ++k;
      check_answer(all[i], files[i], {true, from < to ? r.err.substr(from, to - from) : std::string()}, refused,
                   accepted);
    }
    EXPECT_EQ(r.exit_code, refused ? 2 : 0) << "the exit status must say whether any file was refused";
  }
  std::printf("%s: %zu mutants refused with a clear message, %zu still valid:\n", GetParam().filename().c_str(),
              refused, accepted.size());
  for (const auto &a : accepted) std::printf("  %s\n", a.c_str());
  EXPECT_GT(refused, accepted.size()) << "most mutations must be refused";
  fs::remove_all(dir);
}

INSTANTIATE_TEST_SUITE_P(Shipped, Mutation, ::testing::ValuesIn(shipped_workflows()),
                         [](const ::testing::TestParamInfo<fs::path> &info) { return info.param.stem().string(); });
