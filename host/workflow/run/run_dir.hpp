// The run directory: manifest.json, cases/cNNN/, metrics.csv, train/<model>/, map/.
// The manifest is rewritten atomically after every change, so it always describes whole files.
#pragma once
#include <filesystem>
#include <mutex>
#include <nlohmann/json.hpp>
#include <string>

namespace spreadmap {

namespace fs = std::filesystem;

class RunDirectory {
 public:
  explicit RunDirectory(fs::path root);
  const fs::path &root() const { return root_; }
  fs::path cases() const { return root_ / "cases"; }
  fs::path case_dir(const std::string &id) const { return cases() / id; }
  fs::path heaps() const { return root_ / "heaps"; }
  fs::path metrics_csv() const { return root_ / "metrics.csv"; }
  fs::path train_dir(const std::string &model) const { return root_ / "train" / model; }
  fs::path map_dir() const { return root_ / "map"; }

  // Thread-safe edits of manifest.json: f changes the JSON, which is then written atomically.
  template <class F> void update_manifest(F &&f) {
    std::lock_guard<std::mutex> lock(mutex_);
    f(manifest_);
    save_locked();
  }
  nlohmann::json manifest() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return manifest_;
  }

  static std::string case_id(std::size_t index);  // c000, c001, ...
  static std::string now_iso();                   // UTC, ISO 8601

 private:
  void save_locked();
  fs::path root_;
  nlohmann::json manifest_;
  mutable std::mutex mutex_;
};

}  // namespace spreadmap
