// The package as a user gets it: `cmake --install` of this build into a fresh prefix, then a
// separate project configured with find_package(spreadmap) against that prefix only. For the tests
// that build plugins and programs out of tree (their targets define SPREADMAP_CMAKE_COMMAND and
// SPREADMAP_CXX_COMPILER, workflow.cmake).
#pragma once
#include <gtest/gtest.h>
#include <unistd.h>

#include <string>
#include <utility>
#include <vector>

#include "workflow/process.hpp"

namespace spreadmap::test {

// CMake in a clean environment: no flags or prefixes from the outer build.
inline Outcome cmake(std::vector<std::string> args) {
  return run(
      {std::move(args), SPREADMAP_CMAKE_COMMAND, {{"CXXFLAGS", ""}, {"LDFLAGS", ""}, {"CMAKE_PREFIX_PATH", ""}}, {}});
}

// This build installed into a fresh folder: <temporary folder>/<name>_<pid>/prefix.
struct Package {
  fs::path folder, prefix;
  Outcome install;
};
inline Package install_package(const std::string &name) {
  Package p;
  p.folder = fs::temp_directory_path() / (name + "_" + std::to_string(::getpid()));
  fs::remove_all(p.folder);
  p.prefix = p.folder / "prefix";
  p.install = cmake({"--install", SPREADMAP_BINARY_DIR, "--prefix", p.prefix.string()});
  return p;
}

// A test failure for each of `files` (relative to `prefix`) that is not there.
inline void expect_installed(const fs::path &prefix, const std::vector<std::string> &files) {
  for (const auto &f : files) EXPECT_TRUE(fs::exists(prefix / f)) << f << " is not installed in " << prefix;
}

// Configures `source` into `build` against the package at `prefix`, in Release, with this build's
// compiler; `extra` arguments follow.
inline Outcome configure_against(const fs::path &prefix, const fs::path &source, const fs::path &build,
                                 std::vector<std::string> extra = {}) {
  std::vector<std::string> args = {"-S",
                                   source.string(),
                                   "-B",
                                   build.string(),
                                   "-DCMAKE_PREFIX_PATH=" + prefix.string(),
                                   "-DCMAKE_BUILD_TYPE=Release",
                                   "-DCMAKE_CXX_COMPILER=" SPREADMAP_CXX_COMPILER};
  args.insert(args.end(), extra.begin(), extra.end());
  return cmake(std::move(args));
}

}  // namespace spreadmap::test
