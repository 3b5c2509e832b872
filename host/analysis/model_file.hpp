// model.json: a fitted surrogate with everything needed to use it again.
//   {"format": "spreadmap-model", "version": 1, "plugin": "surrogate/<name>", "plugin_version",
//    "params": {...}, "inputs": [{"name", "unit", "min", "max"}], "outputs": [...],
//    "state": <the plugin's save()>, "training": {...}}
// Written atomically. Numbers are written in the shortest form that reads back bit for bit, so a
// model loaded again predicts identically.
#pragma once
#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace spreadmap::analysis {

struct Variable {
  std::string name, unit;
  double min = 0, max = 0;  // range seen in training (SI)
};

struct ModelFile {
  std::string plugin;                                // "surrogate/<name>"
  std::string plugin_version;                        // "1.0.0"
  nlohmann::json params = nlohmann::json::object();  // validated SI parameters of the instance
  std::vector<Variable> inputs, outputs;
  nlohmann::json state;                                // the plugin's save()
  nlohmann::json training = nlohmann::json::object();  // split, rows, report, source file...
  std::string path;                                    // the file it was read from; empty when made here

  std::string plugin_name() const;  // "<name>" of "surrogate/<name>"
};

void save_model_json(const std::string &path, const ModelFile &model);
// Throws naming the path for a missing file, invalid JSON, another format or version, or a missing key.
ModelFile load_model_json(const std::string &path);

}  // namespace spreadmap::analysis
