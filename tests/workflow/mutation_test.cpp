// Every shipped workflow and example scene file, mutated leaf by leaf, through the real binary
// (`spreadmap validate`): each scalar becomes a word, a NaN, 1e308 and a quantity of the wrong
// dimension, and each key gets a typo. Whatever the mutation, the program must answer as it does for any bad input —
// exit 0 (the mutation happens to be valid) or 2, never a signal, never a raw library message (a JSON or YAML
// exception, a sanitizer report) — and an error must name the file and the key it refuses.
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
    out.push_back({dotted(key) + " renamed " + key.back() + "x", key.back() + "x", doc});
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

}  // namespace

TEST_P(Mutation, EveryMutantGetsACleanAnswer) {
  const fs::path source = SPREADMAP_SOURCE_DIR,
                 dir = fs::temp_directory_path() / ("spreadmap_mutation_" + std::to_string(::getpid()));
  // The mutant sits where the original does relative to the project's root (workflows/, examples/scenes/),
  // beside copies of its folder's other files (particle CSVs); the project's other top folders are
  // linked in, so that a path such as ../examples/calibration/... resolves as it does for the original.
  const fs::path home = dir / fs::relative(GetParam().parent_path(), source);
  fs::create_directories(home);
  for (const char *top : {"examples", "workflows"})
    if (!fs::exists(dir / top)) fs::create_directory_symlink(source / top, dir / top);
  const fs::path file = home / GetParam().filename();
  for (const auto &e : fs::directory_iterator(GetParam().parent_path()))
    if (e.is_regular_file() && e.path().extension() != ".yaml")
      fs::copy_file(e.path(), home / e.path().filename(), fs::copy_options::overwrite_existing);
  std::size_t refused = 0;
  std::vector<std::string> accepted;
  for (const auto &m : mutants(GetParam())) {
    {
      std::ofstream out(file);
      YAML::Emitter emit;
      emit << m.doc;
      out << emit.c_str() << "\n";
    }
    const t::Outcome r = t::run({{"validate", file.string()}, {}, {}, {}});
    SCOPED_TRACE(m.what);
    ASSERT_TRUE(r.exited) << "crashed: " << r.describe();
    EXPECT_EQ(t::crash_marker(r.err), "") << r.describe();
    EXPECT_TRUE(r.exit_code == 0 || r.exit_code == 2) << r.describe();
    if (r.exit_code == 0) {
      accepted.push_back(m.what);
      continue;
    }
    ++refused;
    EXPECT_NE(r.err.find(file.string()), std::string::npos) << "the message does not name the file:\n" << r.err;
    EXPECT_NE(r.err.find(m.key), std::string::npos) << "the message does not name " << m.key << ":\n" << r.err;
  }
  std::printf("%s: %zu mutants refused with a clear message, %zu still valid:\n", GetParam().filename().c_str(),
              refused, accepted.size());
  for (const auto &a : accepted) std::printf("  %s\n", a.c_str());
  EXPECT_GT(refused, accepted.size()) << "most mutations must be refused";
  fs::remove_all(dir);
}

INSTANTIATE_TEST_SUITE_P(Shipped, Mutation, ::testing::ValuesIn(shipped_workflows()),
                         [](const ::testing::TestParamInfo<fs::path> &info) { return info.param.stem().string(); });
